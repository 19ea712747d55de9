#include "doorway_encounters.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <random>

#include "contact_report.h"
#include "doorway_world.h"
#include "lld/follower.h"
#include "office_tour.h"
#include "sim/simulator.h"

namespace rgnav::bench {
namespace {

using geometry::Pose2;

constexpr double kPeriod = 0.05;  // [s] the lld's loop
const auto kPeriodUs = std::chrono::microseconds(50'000);
constexpr double kBaselineLimit_s = 120.0;

Pose2 to_pose(const sim::Pose2& p) { return Pose2(p.x, p.y, p.theta); }

struct Run
{
  bool arrived = false;
  double time_s = 0.0;             // arrival, or the time bound
  int64_t collisions = 0;
  bool deadlock = false;
  double longest_standoff_s = 0.0; // longest stretch with progress by neither party
  double closest_person_m = 1e9;   // smallest surface gap robot-person
  int64_t fallbacks = 0;
  nlohmann::json contacts = nlohmann::json::array();
  std::vector<sim::Encounter> encounters;
  std::string status;              // collision avoidance's at the end
  Eigen::Vector2d end{0.0, 0.0};
};

Run drive(const DoorwayEncounter& e, bool with_person, const lld::LldOptions& lo,
          const collision_avoidance::CaOptions& co, uint64_t seed, double limit_s, bool trace)
{
  // CB_DEBUG_EVERY=N: a trace line every N control periods (default 10).
  const char* every = std::getenv("CB_DEBUG_EVERY");
  const int trace_every = std::max(1, every ? std::atoi(every) : 10);
  sim::World world = e.world;
  if (!with_person) world.people.clear();
  sim::Simulator sim(world, control_sim_options(seed, true));
  sim::TimedCommandSource cmd;
  sim.set_command_source(&cmd);
  lld::Follower follower(lo.follower);
  collision_avoidance::CollisionAvoidance ca(co);
  collision_avoidance::Targets tg;
  tg.goal_id = 1;  // as the planner sends them: one goal, re-sent as the localization corrects
  tg.max_speed = 0.6;
  tg.final_is_goal = true;
  bool sent = false;
  Pose2 sent_correction;
  size_t base_index = 0;
  lld::OdometryInput odi;
  bool have = false;
  int64_t last_id = 0;
  ContactHistory history;
  Run r;
  const double radii = with_person ? world.people[0].radius + sim.options().robot.radius : 0.0;
  double robot_mark = (to_pose(sim.truth()).translation() - e.goal.translation()).norm();
  Eigen::Vector2d person_mark = with_person ? sim.people()[0].center : Eigen::Vector2d::Zero();
  double last_progress = 0.0;
  double cmd_v = 0.0;
  for (int i = 0; i < static_cast<int>(limit_s / kPeriod); ++i) {
    const auto out = sim.step(kPeriodUs);
    const double t = sim.time_s();
    const Pose2 truth = to_pose(sim.truth());
    std::vector<Eigen::Vector2d> people;
    for (const auto& d : sim.people()) people.push_back(d.center);
    history.add(t, truth.translation(), people);
    for (const auto& c : out.collisions) {
      nlohmann::json j = {{"t_s", t}, {"with", c.with}, {"robot_v_cmd_mps", cmd_v},
                          {"mode", collision_avoidance::mode_name(ca.mode())}, {"status", ca.status()}};
      if (with_person)
        if (auto s = history.split(0, 1.0, radii)) j["closed_by"] = s->closed_by;
      r.contacts.push_back(j);
    }
    // Progress of either party ends a standoff: the robot 0.2 m nearer its goal than it was
    // since the last progress (having given way, coming back counts), the person 0.2 m from
    // where they were (either way); a person at their destination is in no standoff.
    const double to_goal = (truth.translation() - e.goal.translation()).norm();
    robot_mark = std::max(robot_mark, to_goal);
    if (to_goal < robot_mark - kProgress_m) {
      robot_mark = to_goal;
      last_progress = t;
    }
    if (with_person) {
      const bool arrived_there = (people[0] - world.people[0].path.back()).norm() < 0.3;
      if (arrived_there || (people[0] - person_mark).norm() >= kProgress_m) {
        person_mark = people[0];
        last_progress = t;
      }
      r.closest_person_m = std::min(r.closest_person_m, (people[0] - truth.translation()).norm() - radii);
    }
    r.longest_standoff_s = std::max(r.longest_standoff_s, t - last_progress);
    if (feed_collision_avoidance(out, ca, &odi)) have = true;
    if (!have) continue;
    const auto now = time::from_utime(sim.now_utime());
    // Targets are given in the world; a perfect localizer re-expresses the remaining ones in
    // the drifting odometry frame whenever that correction has moved (as on the courses).
    const Pose2 odom_from_world = odi.pose * truth.inverse();
    const Pose2 change = sent_correction.inverse() * odom_from_world;
    if (!sent || change.translation().norm() > 0.05 || std::fabs(change.theta()) > 0.01) {
      const size_t from = sent ? std::min(ca.next_target(), tg.poses.size() - 1) : 0;
      base_index += from;
      tg.poses.clear();
      for (size_t q = base_index; q < e.targets.size(); ++q) tg.poses.push_back(odom_from_world * e.targets[q]);
      ca.set_targets(tg);
      sent_correction = odom_from_world;
      sent = true;
    }
    hand_over_trajectory(ca, follower, lo.follower, now, &last_id);
    const auto& st = follower.step(now, kPeriod, &odi);
    cmd.set(sim.now_utime(), {st.command.v, st.command.omega}, lo.loop.command_deadline_ms * 1000);
    cmd_v = st.command.v;
    if (trace && i % trace_every == 0) {
      std::cerr << "t=" << t << " robot " << truth.x() << "," << truth.y() << "," << truth.theta() << " "
                << collision_avoidance::mode_name(ca.mode()) << " '" << ca.status() << "' v " << st.command.v
                << " w " << st.command.omega;
      for (const auto& p : people) std::cerr << " person " << p.x() << "," << p.y();
      // What the local map holds near the robot (odom frame): the nearest point (robot frame).
      const Eigen::Vector2d here = odi.pose.translation();
      double best = 1e9;
      Eigen::Vector2d nearest = Eigen::Vector2d::Zero();
      for (const auto& p : ca.map().points())
        if ((p - here).norm() < best) {
          best = (p - here).norm();
          nearest = odi.pose.inverse() * p;
        }
      std::cerr << " clear " << best << " at " << nearest.x() << "," << nearest.y() << " moving "
                << ca.map().clearance_moving(here, 1.0);
      // What collision avoidance takes for people (odom frame): CB_DEBUG_TRACKS=1.
      if (std::getenv("CB_DEBUG_TRACKS")) {
        for (const auto& tr : ca.map().tracker().tracks())
          if (!tr.centroids.empty())
            std::cerr << " track" << tr.id << (tr.moved ? "m" : "") << " " << tr.centroids.back().second.x() << ","
                      << tr.centroids.back().second.y() << " v " << tr.velocity.x() << "," << tr.velocity.y() << " steady "
                      << tr.moving_steady;
        for (const auto& m : ca.map().tracker().last_seen_movers())
          if ((m.position - here).norm() < 4.0)
            std::cerr << " stopped " << m.position.x() << "," << m.position.y() << " walking " << m.walking.x() << ","
                      << m.walking.y() << " steady " << m.moving_steady;
        std::cerr << " odom_from_world " << odom_from_world.x() << "," << odom_from_world.y() << ","
                  << odom_from_world.theta();
      }
      std::cerr << "\n";
    }
    if (ca.mode() == collision_avoidance::Mode::kArrived) {
      r.arrived = true;
      break;
    }
  }
  r.time_s = sim.time_s();
  r.collisions = sim.collisions();
  r.deadlock = r.longest_standoff_s >= kDeadlock_s;
  r.fallbacks = ca.fallbacks();
  r.encounters = sim.people_model().encounters();
  r.status = ca.status();
  r.end = to_pose(sim.truth()).translation();
  return r;
}

double percentile(std::vector<double> v, double q)
{
  if (v.empty()) return -1.0;
  std::sort(v.begin(), v.end());
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(std::ceil(q * v.size())) - 1);
  return v[k];
}

}  // namespace

nlohmann::json doorway_encounters(const lld::LldOptions& lo, const collision_avoidance::CaOptions& co, int n,
                                  uint64_t seed, int only)
{
  std::mt19937 rng(static_cast<uint32_t>(seed + 7));
  const double clearance = co.planner.robot_radius + co.planner.safety_margin;
  const bool trace = std::getenv("CB_DEBUG") != nullptr;
  int run_count = 0, resolved = 0, deadlocks = 0, baseline_failed = 0;
  int64_t collisions = 0;
  std::vector<double> lost;
  std::map<std::string, std::map<std::string, double>> by_kind;
  std::map<std::string, int> choices, outcomes;
  nlohmann::json runs = nlohmann::json::array(), contacts = nlohmann::json::array();
  for (int k = 0; k < n; ++k) {
    const DoorwayEncounter e = draw_doorway_encounter(rng, k, clearance);
    if (only >= 0 && k != only) continue;  // the others are drawn, not run
    const uint64_t run_seed = seed + 5000 + static_cast<uint64_t>(k);
    const Run alone = drive(e, false, lo, co, run_seed, kBaselineLimit_s, false);
    if (!alone.arrived) ++baseline_failed;
    const double bound = (alone.arrived ? alone.time_s : kBaselineLimit_s) + kResolveBound_s;
    const Run r = drive(e, true, lo, co, run_seed, bound, trace);
    ++run_count;
    const bool ok = r.arrived && r.time_s <= bound;
    resolved += ok ? 1 : 0;
    deadlocks += r.deadlock ? 1 : 0;
    collisions += r.collisions;
    auto& kind = by_kind[e.kind];
    kind["encounters"] += 1;
    kind["resolved"] += ok ? 1 : 0;
    kind["collisions"] += static_cast<double>(r.collisions);
    kind["deadlocks"] += r.deadlock ? 1 : 0;
    if (ok && alone.arrived) {
      lost.push_back(r.time_s - alone.time_s);
      kind["time_lost_s_sum"] += r.time_s - alone.time_s;
    }
    nlohmann::json met = nlohmann::json::array();
    for (const auto& m : r.encounters) {
      choices[sim::to_string(m.choice)]++;
      if (m.no_room) outcomes["no room for the choice"]++;
      if (m.stood_aside) outcomes["stood aside"]++;
      if (m.went_around) outcomes["went around"]++;
      if (m.turned_back) outcomes["turned back"]++;
      met.push_back({{"t_s", m.t}, {"choice", sim::to_string(m.choice)}, {"patience_s", m.patience},
                     {"no_room", m.no_room}, {"stood_aside", m.stood_aside}, {"went_around", m.went_around},
                     {"turned_back", m.turned_back}});
    }
    const auto& person = e.world.people[0];
    runs.push_back({{"encounter", k},
                    {"kind", e.kind},
                    {"width_m", e.width},
                    {"depth_m", e.depth},
                    {"person_speed_mps", person.speed},
                    {"person_personal_space_m", person.personal_space},
                    {"person_lead_s", e.person_lead_s},
                    {"resolved", ok},
                    {"time_s", r.time_s},
                    {"time_alone_s", alone.time_s},
                    {"time_lost_s", ok && alone.arrived ? r.time_s - alone.time_s : -1.0},
                    {"collisions", r.collisions},
                    {"deadlock", r.deadlock},
                    {"longest_standoff_s", r.longest_standoff_s},
                    {"closest_person_m", r.closest_person_m},
                    {"fallbacks", r.fallbacks},
                    {"status_at_end", r.status},
                    {"end", {r.end.x(), r.end.y()}},
                    {"person_met_robot", met}});
    for (auto c : r.contacts) {
      c["encounter"] = k;
      contacts.push_back(c);
    }
    std::cerr << "doorway encounter " << k << " (" << e.kind << " " << e.width << " m): "
              << (ok ? "resolved" : "NOT resolved") << " in " << r.time_s << " s (alone " << alone.time_s
              << " s), collisions " << r.collisions << (r.deadlock ? ", DEADLOCK" : "") << ", standoff "
              << r.longest_standoff_s << " s, person:";
    for (const auto& m : r.encounters) std::cerr << " " << sim::to_string(m.choice) << (m.turned_back ? "/turned back" : "");
    std::cerr << "\n";
  }
  nlohmann::json kinds = nlohmann::json::object();
  for (auto& [name, v] : by_kind) {
    kinds[name] = {{"encounters", v["encounters"]},
                   {"resolved_ratio", v["encounters"] > 0 ? v["resolved"] / v["encounters"] : 0.0},
                   {"collisions", v["collisions"]},
                   {"deadlocks", v["deadlocks"]},
                   {"time_lost_s_mean", v["resolved"] > 0 ? v["time_lost_s_sum"] / v["resolved"] : -1.0}};
  }
  double lost_sum = 0.0;
  for (double l : lost) lost_sum += l;
  return {{"encounters", run_count},
          {"resolved", resolved},
          {"resolved_ratio", run_count ? static_cast<double>(resolved) / run_count : 0.0},
          {"collisions", collisions},
          {"deadlocks", deadlocks},
          {"time_lost_s_mean", lost.empty() ? -1.0 : lost_sum / static_cast<double>(lost.size())},
          {"time_lost_s_p90", percentile(lost, 0.9)},
          {"time_lost_s_max", percentile(lost, 1.0)},
          {"baseline_failed", baseline_failed},
          {"by_kind", kinds},
          {"person_choices", choices},
          {"person_outcomes", outcomes},
          {"definitions",
           "resolved: the robot arrived at its goal beyond the opening within its own time there without the "
           "person plus 60 s. deadlock: for 20 s neither party made progress (the robot came no closer to its "
           "goal than 0.2 m nearer than at its last progress or the farthest since, the person moved less than "
           "0.2 m and was not at their destination). collision: a simulator "
           "contact (the robot's own motion into a wall or a person), as on the obstacle courses. time lost: "
           "time to the goal with the person minus without, over the resolved encounters."},
          {"contacts", contacts},
          {"runs", runs}};
}

}  // namespace rgnav::bench
