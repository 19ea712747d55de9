#include "course_drive.h"

#include <cmath>
#include <iostream>
#include <limits>

#include "config/config.h"
#include "config/finish_except.h"
#include "lld/follower.h"

#include "contact_report.h"
#include "office_tour.h"

namespace rgnav::bench {

namespace {

using geometry::Pose2;

// The lld's loop (names of their own: this file may share a unity batch with office_tour.cpp).
constexpr double kDrivePeriod = 0.05;
const auto kDrivePeriodUs = std::chrono::microseconds(50'000);

Pose2 true_pose(const sim::Pose2& p) { return Pose2(p.x, p.y, p.theta); }

// One contact: what was hit, the robot's speed just before (the simulator stops it at contact),
// and for a person who closed the gap over the last 1 and 3 seconds.
nlohmann::json contact_json(int course, const sim::Simulator& sim, const sim::CollisionEvent& e,
                            const ContactHistory& history, double true_v, double cmd_v,
                            const collision_avoidance::CollisionAvoidance& ca)
{
  nlohmann::json j = {{"course", course},
                      {"t_s", sim.time_s()},
                      {"with", e.with},
                      {"robot_v_true_mps", true_v},
                      {"robot_v_cmd_mps", cmd_v},
                      {"mode", collision_avoidance::mode_name(ca.mode())},
                      {"status", ca.status()}};
  const auto& people = sim.world().people;
  for (size_t p = 0; p < people.size(); ++p) {
    if (e.with != "person " + people[p].name) continue;
    const double radii = people[p].radius + sim.options().robot.radius;
    for (double w : {1.0, 3.0}) {
      if (auto s = history.split(p, w, radii)) {
        const std::string key = w < 2.0 ? "1s" : "3s";
        j["gap_before_" + key + "_m"] = s->gap_before_m;
        j["robot_closing_" + key + "_m"] = s->robot_closing_m;
        j["person_closing_" + key + "_m"] = s->person_closing_m;
        if (w < 2.0) {
          j["closed_by"] = s->closed_by;
          j["person_speed_mps"] = s->person_speed_mps;
        }
      }
    }
    if (auto s = history.split(p, 0.3, radii))
      j["robot_toward_person_mps"] = s->window_s > 0 ? s->robot_closing_m / s->window_s : 0.0;
  }
  return j;
}

// Every tick: the nearest obstacle point in the base frame, the nearest possibly moving and
// predicted ones, and where the people are (phantom movers show here).
void trace_nearest(const sim::Simulator& sim, const collision_avoidance::CollisionAvoidance& ca, const Pose2& odom)
{
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector2d nearest(0.0, 0.0);
  for (const auto& q : ca.map().points()) {
    const double d = (q - odom.translation()).norm();
    if (d < best) {
      best = d;
      nearest = q;
    }
  }
  const Eigen::Vector2d in_base = odom.inverse() * nearest;
  std::cerr << "  t=" << sim.time_s() << " nearest base " << in_base.x() << "," << in_base.y() << " d=" << best
            << " moving_d=" << ca.map().clearance_moving(odom.translation(), 3.0)
            << " predicted_d=" << ca.map().clearance_predicted(odom.translation(), 3.0) << " people";
  for (const auto& disc : sim.people()) std::cerr << " " << disc.center.x() << "," << disc.center.y();
  std::cerr << " stopped movers (odom)";
  for (const auto& m : ca.map().tracker().last_seen_movers()) std::cerr << " " << m.position.x() << "," << m.position.y();
  std::cerr << " '" << ca.status() << "'\n";
}

}  // namespace

DriveConfig load_drive_config(const std::string& config_dir)
{
  DriveConfig c;
  c.robot = config::load_robot_description_file(config_dir + "/robot.yaml");
  const auto lcfg = config::Config::load(config_dir + "/lld.yaml");
  c.lld = lld::load_lld_options(lcfg, c.robot);
  config::finish_except(lcfg, {"node"});
  const auto ccfg = config::Config::load(config_dir + "/collision_avoidance.yaml");
  c.ca = collision_avoidance::load_ca_options(ccfg, c.robot);
  config::finish_except(ccfg, {"node"});
  return c;
}

CourseDriveResult drive_course(const Course& course, int index, const lld::LldOptions& lo,
                               const collision_avoidance::CaOptions& co, const CourseDriveOptions& options)
{
  sim::Simulator sim(course.world, options.sim);
  sim::TimedCommandSource cmd;
  sim.set_command_source(&cmd);
  lld::Follower f(lo.follower);
  collision_avoidance::CollisionAvoidance ca(co);
  collision_avoidance::Targets tg;
  tg.poses = course.targets;
  tg.max_speed = options.max_speed;
  tg.final_is_goal = true;
  ca.set_targets(tg);
  Pose2 sent_correction;   // odom_from_world the targets were last expressed with
  size_t base_index = 0;   // course target index of tg.poses[0]
  lld::OdometryInput odi;
  bool have = false;
  int64_t last_id = 0;
  ContactHistory history;
  double true_v_before = 0.0, cmd_v_before = 0.0;  // the step before the newest (contact stops the robot)
  CourseDriveResult r;
  for (int i = 0; i < static_cast<int>(options.time_limit_s / kDrivePeriod); ++i) {
    const auto out = sim.step(kDrivePeriodUs);
    {
      std::vector<Eigen::Vector2d> people;
      for (const auto& disc : sim.people()) people.push_back(disc.center);
      history.add(sim.time_s(), true_pose(sim.truth()).translation(), people);
    }
    for (const auto& e : out.collisions) {
      r.contacts.push_back(contact_json(index, sim, e, history, true_v_before, cmd_v_before, ca));
      if (options.trace)
        std::cerr << "course " << index << " collision at t=" << sim.time_s() << " " << r.contacts.back().dump() << "\n";
    }
    if (!out.odometry.empty()) true_v_before = out.odometry.back().true_v;
    if (feed_collision_avoidance(out, ca, &odi)) have = true;
    if (options.after_step) options.after_step(sim, out, ca);
    const auto now = time::from_utime(sim.now_utime());
    // Targets are given in the world; the odometry drifts (turning on the spot most: 2 %
    // rotation scale error). Without a localizer an odometry-frame goal ends up in a wall
    // after a few back-offs (measured: 1.2 m off after 90 s). So, as the planner will
    // with localization, the remaining targets are re-expressed in the odometry frame from
    // the true pose (a perfect localizer) whenever that correction has moved.
    if (have) {
      const Pose2 odom_from_world = odi.pose * true_pose(sim.truth()).inverse();
      const Pose2 change = sent_correction.inverse() * odom_from_world;
      if (change.translation().norm() > 0.05 || std::fabs(change.theta()) > 0.01) {
        const size_t from = std::min(ca.next_target(), tg.poses.size() - 1);
        collision_avoidance::Targets moved = tg;
        moved.poses.clear();
        for (size_t q = base_index + from; q < course.targets.size(); ++q)
          moved.poses.push_back(odom_from_world * course.targets[q]);
        base_index += from;
        tg = moved;
        ca.set_targets(tg);
        sent_correction = odom_from_world;
      }
    }
    hand_over_trajectory(ca, f, lo.follower, now, &last_id);
    const auto& st = f.step(now, kDrivePeriod, have ? &odi : nullptr);
    cmd.set(sim.now_utime(), {st.command.v, st.command.omega}, lo.loop.command_deadline_ms * 1000);
    cmd_v_before = st.command.v;
    if (options.trace && i % 10 == 0)
      std::cerr << "t=" << sim.time_s() << " truth=" << sim.truth().x << "," << sim.truth().y << " th=" << sim.truth().theta
                << " next=" << ca.next_target() << " mode=" << collision_avoidance::mode_name(ca.mode()) << " '" << ca.status()
                << "' v=" << st.command.v << " w=" << st.command.omega << " lld=" << static_cast<int>(st.state)
                << " id=" << st.trajectory_id << " len=" << (ca.active() ? ca.active()->chain.length() : -1)
                << " nseg=" << (ca.active() ? ca.active()->chain.size() : 0) << " map=" << ca.map().size()
                << " clr=" << ca.map().clearance(odi.pose.translation(), 3.0) << " odom=" << odi.pose.x() << ","
                << odi.pose.y() << "\n";
    if (options.trace_nearest) trace_nearest(sim, ca, odi.pose);
    if (ca.mode() == collision_avoidance::Mode::kArrived) {
      r.arrived = true;
      break;
    }
  }
  r.time_s = sim.time_s();
  r.collisions = sim.collisions();
  r.fallbacks = ca.fallbacks();
  r.replans = ca.replans();
  r.end = sim.truth();
  r.mode = collision_avoidance::mode_name(ca.mode());
  return r;
}

}  // namespace rgnav::bench
