// Builds chains of primitives from the robot's pose to the next targets (diss. 5.5.3) and
// checks them against the local map with the robot's footprint (a circle) plus a safety
// margin. Candidates: a G1 clothoid, a G2 line-turn-line, Dubins paths, detours through
// lateral via-poses, and a turn in place first when the target is behind. The feasible one
// with the shortest predicted traversal time (its velocity profile) wins. The first metre
// keeps an extra margin from what may be moving (people step in from the side); static
// obstacles (door frames) need only the plain margin.
#pragma once

#include <optional>
#include <vector>

#include "collision_avoidance/local_map.h"
#include "trajectory/chain.h"
#include "trajectory/velocity_profile.h"

namespace rgnav::collision_avoidance {

struct PlannerOptions
{
  double robot_radius = 0.26;     // [m] B21r footprint
  double safety_margin = 0.10;    // [m] on top of the radius
  double kappa_max = 2.5;         // [1/m] sharpest curvature the drive may follow
  double check_step = 0.05;       // [m] footprint checks along the chain
  std::vector<double> detour_offsets{0.3, 0.6, 0.9, 1.2};  // [m] lateral via-pose offsets
  double max_length_ratio = 3.0;  // candidates longer than this times the distance are dropped
  double turn_first_angle = 1.6;  // [rad] bearing to the target beyond which to turn in place first
  trajectory::Limits limits;      // for the time prediction (the lld's profile limits)
  // Slow down near obstacles (shorter stopping distance where people may step in): a
  // segment whose clearance exceeds the required one by less than slow_band gets a speed
  // limit between slow_speed and the full speed.
  double slow_band = 0.8;         // [m]
  // The first near_length of a chain (what the robot drives before it could replan and stop)
  // must keep near_margin more: people step in from the side faster than the map ages.
  double near_length = 1.0;       // [m]
  double near_margin = 0.2;       // [m]
  double slow_speed = 0.2;        // [m/s]
};

// The clearance a chain needs at arc length s when it starts with clearance c0: the full
// `clearance`, except that a robot already closer than that to something may leave (first_collision):
// never closer, and away at 0.5 m per metre, or within a metre when only a few centimetres short.
double required_clearance(double clearance, double c0, double s);

// Where the footprint first touches the map along a chain (arc length), if anywhere, from
// s_from on; turns in place are checked at their position. Where the chain starts closer
// than `clearance` to something, it may move away (clearance growing with the distance
// driven) but not get closer: otherwise a robot that once got close would stay stuck.
std::optional<double> first_collision(const trajectory::Chain& chain, const LocalMap& map, double clearance,
                                      double step, double s_from = 0.0);

// first_collision, plus the extra margin from possibly moving points on [s_from, s_from + near_length].
std::optional<double> first_collision_near(const trajectory::Chain& chain, const LocalMap& map,
                                           const PlannerOptions& options, double s_from);

struct PlannedChain
{
  trajectory::Chain chain;
  double predicted_time = 0.0;  // [s] from its velocity profile
  double min_clearance = 0.0;   // [m] nearest obstacle to the path centre line
};

class ChainPlanner
{
 public:
  explicit ChainPlanner(const PlannerOptions& options) : options_(options) {}

  // A collision-free chain from `start` through `goals` (driving order; their headings are
  // the wanted headings on arrival), starting at speed v_start; nothing if no candidate is free.
  std::optional<PlannedChain> plan(const Pose2& start, double v_start, const std::vector<Pose2>& goals,
                                   const LocalMap& map, double v_max) const;

  // A chain along a detour found elsewhere (grid_path): through `corners` (odom frame, the
  // last is the target), arriving with final_heading if given. Clothoids through the corners
  // when free, else straight legs with turns on the spot (only from standing).
  std::optional<PlannedChain> plan_along(const Pose2& start, double v_start, const std::vector<Eigen::Vector2d>& corners,
                                         std::optional<double> final_heading, const LocalMap& map, double v_max) const;

  const PlannerOptions& options() const { return options_; }

 private:
  // Speed limits from clearance, the time prediction and the clearance figure.
  std::optional<PlannedChain> finish(trajectory::Chain total, double v_start, const LocalMap& map,
                                     const trajectory::Limits& lim) const;
  std::vector<trajectory::Chain> candidates(const Pose2& from, const Pose2& to, bool standing) const;
  bool acceptable(const trajectory::Chain& c, double direct) const;

  const PlannerOptions options_;
};

}  // namespace rgnav::collision_avoidance
