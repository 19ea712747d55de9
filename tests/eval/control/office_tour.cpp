#include "office_tour.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include "collision_avoidance/collision_avoidance.h"
#include "lld/follower.h"
#include "sim/simulator.h"
#include "sim/tour_planner.h"
#include "tour_runner/tour.h"
#include "tour_runner/tour_sequencer.h"

namespace rgnav::bench {

using geometry::Pose2;

namespace {

constexpr double kPeriod = 0.05;  // [s] the lld's loop
const auto kPeriodUs = std::chrono::microseconds(50'000);

Pose2 to_pose(const sim::Pose2& p) { return Pose2(p.x, p.y, p.theta); }

std::string people_text(const sim::Simulator& sim)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(2);
  for (const auto& d : sim.people()) s << " " << d.center.x() << "," << d.center.y();
  return s.str();
}

}  // namespace

sim::SimulatorOptions control_sim_options(uint64_t seed, bool laser)
{
  sim::SimulatorOptions o;
  o.seed = seed;
  o.laser_enabled = laser;
  o.odometry.scale_translation = 0.01;
  o.odometry.scale_rotation = -0.02;
  o.odometry.bias_rotation_per_m = 0.005;
  o.odometry.sigma_translation = 0.01;
  o.odometry.sigma_rotation = 0.02;
  o.odometry.sigma_rotation_per_m = 0.005;
  return o;
}

void hand_over_trajectory(collision_avoidance::CollisionAvoidance& ca, lld::Follower& follower,
                          const lld::FollowerOptions& options, time::Time now, int64_t* last_id)
{
  const auto& fs = follower.status();
  ca.on_drive_feedback({fs.trajectory_id, static_cast<int>(fs.state), fs.progress, fs.cross_track, fs.command.v});
  if (auto traj = ca.update(now)) {
    if (traj->id != *last_id) {
      follower.replace(lld::make_plan(*traj, options, follower.last_command().v), now);
      *last_id = traj->id;
    } else {
      follower.refresh(traj->id, now);
    }
  }
}

bool feed_collision_avoidance(const sim::StepOutput& out, collision_avoidance::CollisionAvoidance& ca,
                              lld::OdometryInput* odometry)
{
  for (const auto& o : out.odometry) {
    *odometry = {to_pose(o.odom_from_base), o.v, o.omega, time::from_utime(o.utime)};
    ca.on_odometry(odometry->stamp, odometry->pose, o.v);
  }
  for (const auto& s : out.scans) {
    std::vector<collision_avoidance::PolarReading> readings;
    for (size_t b = 0; b < s.ranges.size(); ++b)
      if (s.ranges[b] > s.range_min) readings.push_back({s.angle_min + b * s.angle_increment, s.ranges[b]});
    ca.on_scan(time::from_utime(s.utime), readings, s.range_max);
  }
  return !out.odometry.empty();
}

std::vector<Eigen::Vector2d> demo_tour(const sim::World& world)
{
  if (!world.tour.empty()) return world.tour;
  sim::TourOptions o;
  o.margin = 0.15;  // deploy/cli/demo.sh
  const sim::Tour tour = sim::plan_tour(world, sim::RobotOptions{}, o);
  return tour.collision_free ? tour.waypoints : std::vector<Eigen::Vector2d>{};
}

TourRunResult run_tour(const sim::World& world_in, const std::vector<Eigen::Vector2d>& world_points,
                       const lld::LldOptions& lld_options, const collision_avoidance::CaOptions& ca_options,
                       const TourRunOptions& options)
{
  sim::World world = world_in;
  for (auto& p : world.people) p.start_delay += options.people_delay_s;
  const Pose2 world_from_start = to_pose(world.start);
  const std::vector<Eigen::Vector2d> targets =
      tour_runner::densify(world_points, world_from_start.translation(), options.max_spacing_m);
  tour_runner::SequencerOptions so;
  so.reach_radius = options.reach_radius_m;
  tour_runner::TourSequencer sequencer(so, targets);

  sim::Simulator sim(world, control_sim_options(options.seed, true));
  sim::TimedCommandSource cmd;
  sim.set_command_source(&cmd);
  lld::Follower follower(lld_options.follower);
  collision_avoidance::CollisionAvoidance ca(ca_options);

  TourRunResult r;
  r.targets = targets.size();
  lld::OdometryInput odi;
  bool have = false;
  int64_t last_id = 0;
  double last_sent_s = -1e9, last_reached_s = 0.0;
  Eigen::Vector2d waiting_from = world_from_start.translation();
  const int steps = static_cast<int>(options.time_limit_s / kPeriod);
  for (int i = 0; i < steps && !sequencer.done(); ++i) {
    const auto out = sim.step(kPeriodUs);
    if (feed_collision_avoidance(out, ca, &odi)) have = true;
    if (!have) continue;
    const auto now = time::from_utime(sim.now_utime());
    const Pose2 world_from_base = to_pose(sim.truth());
    const bool advanced = sequencer.update(world_from_base);
    if (advanced) {
      const double stall = sim.time_s() - last_reached_s;
      if (stall > r.longest_stall_s) {
        r.longest_stall_s = stall;
        r.stall_at = waiting_from;
        r.stall_target = sequencer.reached();
      }
      last_reached_s = sim.time_s();
      waiting_from = world_from_base.translation();
    }
    if (sequencer.done()) break;
    // tour_runner: on every advance and on its cadence, the upcoming targets in the odometry
    // frame (here through a perfect localizer), headed 0, with the goal id it publishes.
    if (advanced || sim.time_s() - last_sent_s >= options.resend_period_s) {
      const Pose2 odom_from_world = odi.pose * world_from_base.inverse();
      collision_avoidance::Targets t;
      t.goal_id = sequencer.goal_id();
      t.max_speed = options.max_speed;
      const auto upcoming = sequencer.upcoming();
      for (const auto& p : upcoming) t.poses.push_back(Pose2(odom_from_world * p, 0.0));
      t.final_is_goal = sequencer.reached() + upcoming.size() >= sequencer.size();
      ca.set_targets(t);
      last_sent_s = sim.time_s();
    }
    hand_over_trajectory(ca, follower, lld_options.follower, now, &last_id);
    const auto& st = follower.step(now, kPeriod, &odi);
    cmd.set(sim.now_utime(), {st.command.v, st.command.omega}, lld_options.loop.command_deadline_ms * 1000);
    if (options.trace && i % 20 == 0)
      std::cerr << "t=" << sim.time_s() << " at " << world_from_base.x() << "," << world_from_base.y()
                << " target " << sequencer.reached() + 1 << "/" << sequencer.size() << " "
                << collision_avoidance::mode_name(ca.mode()) << " '" << ca.status() << "' v " << st.command.v << " w "
                << st.command.omega << " lld " << static_cast<int>(st.state) << " people" << people_text(sim) << "\n";
  }
  const double stall = sim.time_s() - last_reached_s;
  if (!sequencer.done() && stall > r.longest_stall_s) {
    r.longest_stall_s = stall;
    r.stall_at = waiting_from;
    r.stall_target = sequencer.reached() + 1;
  }
  r.reached = sequencer.reached();
  r.time_s = sim.time_s();
  r.collisions = sim.collisions();
  r.fallbacks = ca.fallbacks();
  return r;
}

}  // namespace rgnav::bench
