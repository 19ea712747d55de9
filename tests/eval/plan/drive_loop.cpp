#include "drive_loop.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "config/config.h"
#include "config/finish_except.h"
#include "config/robot_description.h"
#include "office_tour.h"
#include "sim/sim_options.h"

namespace rgnav::plan_eval {

DriveChainOptions load_drive_chain(const DriveChainFiles& files, const config::RobotDescription& robot)
{
  DriveChainOptions o;
  const auto sim_cfg = config::Config::load(files.sim);
  o.sim = sim::load_simulator_options(sim_cfg, robot);
  config::finish_except(sim_cfg, {"node", "channels", "sim", "protocol"});
  const auto plan_cfg = config::Config::load(files.planner);
  o.planner = planner::load_planner_options(plan_cfg, robot);
  config::finish_except(plan_cfg, {"node", "channels", "pose", "persist"});
  const auto lld_cfg = config::Config::load(files.lld);
  o.lld = lld::load_lld_options(lld_cfg, robot);
  config::finish_except(lld_cfg, {"node"});
  const auto ca_cfg = config::Config::load(files.ca);
  o.ca = collision_avoidance::load_ca_options(ca_cfg, robot).ca;
  config::finish_except(ca_cfg, {"node"});
  return o;
}

namespace {
geometry::Pose2 to_pose(const sim::Pose2& p) { return geometry::Pose2(p.x, p.y, p.theta); }
}  // namespace

DriveLoop::DriveLoop(const sim::World& world, const sim::SimulatorOptions& sim_options, const lld::LldOptions& lld,
                     const collision_avoidance::CaOptions& ca)
    : lld_(lld), sim_(world, sim_options), follower_(lld.follower), ca_(ca)
{
  sim_.set_command_source(&cmd_);
  truth_ = to_pose(sim_.truth());
}

const sim::StepOutput& DriveLoop::sense()
{
  out_ = sim_.step(kPeriodUs);
  for (const auto& c : out_.collisions) contacts_.push_back(c.with);
  if (bench::feed_collision_avoidance(out_, ca_, &odometry_)) have_odometry_ = true;
  for (const auto& o : out_.odometry) {
    truth_ = to_pose(o.world_from_base);
    true_distance_ = o.true_distance;
    truth_utime_ = o.utime;
  }
  return out_;
}

void DriveLoop::act()
{
  const int64_t utime = sim_.now_utime();
  const auto now = time::from_utime(utime);
  bench::hand_over_trajectory(ca_, follower_, lld_.follower, now, &last_trajectory_id_);
  const auto& st = follower_.step(now, kPeriod, &odometry_);
  cmd_.set(utime, {st.command.v, st.command.omega}, lld_.loop.command_deadline_ms * 1000);
}

void DriveLoop::command(double v, double omega)
{
  cmd_.set(sim_.now_utime(), {v, omega}, lld_.loop.command_deadline_ms * 1000);
}

bool DriveLoop::cannot_pass() const
{
  // As planner::cannot_pass reads CA_STATUS: yielding to a person is not blocked.
  const auto mode = ca_.mode();
  return mode == collision_avoidance::Mode::kBlocked || mode == collision_avoidance::Mode::kReactive;
}

std::vector<std::string> DriveLoop::take_contacts() { return std::exchange(contacts_, {}); }

double DriveLoop::nearest_person() const
{
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : sim_.people()) best = std::min(best, (p.center - truth_.translation()).norm() - p.radius);
  return best;
}

}  // namespace rgnav::plan_eval
