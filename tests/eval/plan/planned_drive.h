// The simulator, collision avoidance, the lld follower and rgnav's Planner in lock-step at the
// lld's 20 Hz, as the control benchmark's office tour runs the first three (office_tour.h): the
// planner in place of the tour sequencer, fed by a perfect localizer (the true pose in a region
// with the odometry pose of the same time; the region changes as the localizer hands over: on
// leaving the current region's freespace or measurement rectangle, to the neighbour beyond a
// gateway within 1.5 m that holds the place)
// and told "cannot pass" while collision avoidance is blocked or in its reactive fallback; its
// targets go to collision avoidance.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "bench_world.h"
#include "collision_avoidance/ca_options.h"
#include "collision_avoidance/collision_avoidance.h"
#include "drive_loop.h"
#include "lld/lld_options.h"
#include "planner/planner.h"
#include "planner/planner_options.h"
#include "sim/simulator.h"

namespace rgnav::plan_eval {

struct ClosedLoopSetup
{
  const planner::PlannerOptions& planner;
  const lld::LldOptions& lld;
  const collision_avoidance::CaOptions& ca;
  sim::SimulatorOptions sim;
};

// The planner's targets as collision avoidance takes them (TARGETS).
collision_avoidance::Targets to_ca_targets(const planner::TargetList& targets);

class PlannedDrive
{
 public:
  // The robot starts at world.start; the planner holds w.map.
  PlannedDrive(const sim::World& world, const sim::SimulatorOptions& sim_options, const localize_eval::BenchWorld& w,
               const ClosedLoopSetup& setup);

  static constexpr double kPeriod = DriveLoop::kPeriod;

  // One period.
  void step();

  planner::Planner& planner() { return planner_; }
  const planner::Planner& planner() const { return planner_; }
  const sim::Simulator& sim() const { return loop_.sim(); }
  const collision_avoidance::CollisionAvoidance& ca() const { return loop_.ca(); }
  const geometry::Pose2& truth() const { return loop_.truth(); }
  double true_distance() const { return loop_.true_distance(); }   // [m] driven since the start
  int64_t region() const { return region_; }                // the region the planner is told
  double planner_cpu_s() const { return planner_cpu_s_; }
  // Distinct planner reports seen ("status: reason"), a few.
  const std::set<std::string>& reasons() const { return reasons_; }
  // What the robot hit since the last call (the simulator's names: "lab.table.top", "person p2").
  std::vector<std::string> take_contacts() { return loop_.take_contacts(); }
  // [m] from the robot's centre to the nearest person's edge (infinity: nobody).
  double nearest_person() const { return loop_.nearest_person(); }
  // The first `n` targets last sent, in the world frame.
  std::string targets_text(size_t n) const;

 private:
  int64_t region_of(const geometry::Pose2& truth) const;

  const localize_eval::BenchWorld& w_;
  const ClosedLoopSetup& setup_;
  DriveLoop loop_;
  planner::Planner planner_;
  int64_t region_ = 0;
  double planner_cpu_s_ = 0;
  std::string last_reason_;
  std::set<std::string> reasons_;
  planner::TargetList last_targets_;
};

}  // namespace rgnav::plan_eval
