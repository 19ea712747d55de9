// The reactive fallback when no chain is free (Holz et al., "Continuous 3D sensing for
// navigation and SLAM in cluttered and dynamic environments", section 5, after Lingemann et
// al. 2005): slow down for obstacles in the virtual corridor ahead, stop below dto_min, turn
// on the spot once stopped, and steer toward the freespace orientation
//
//   alpha_free = atan2(sum sin(th_i) f_th(th_i) f_d(d_i), sum cos(th_i) f_th(th_i) f_d(d_i))   (5)
//   f_th(th) = cos(th / 1.2),  f_d(d) = 1 / (1 + exp(-(d - dto_max) / dto_min))                (6)
//
// over the readings (th_i, d_i) in polar form around the robot.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace rgnav::collision_avoidance {

struct ReactiveOptions
{
  double dto_min = 0.45;         // [m] stop when the corridor is blocked this close (from the centre)
  double dto_max = 1.5;          // [m] start slowing down
  double corridor_half_width = 0.36;  // [m] robot radius + margin
  double v_max = 0.3;            // [m/s] speed of reactive motion
  double step_length = 0.5;      // [m] length of a reactive arc
  double max_turn = 1.57;        // [rad] largest turn in place per decision
};

// Readings around the robot in its base frame: bearing and distance; a no-return beam is a
// reading at its maximum range.
struct PolarReading
{
  double bearing;
  double range;
};

double freespace_orientation(const std::vector<PolarReading>& readings, const ReactiveOptions& o);

struct ReactiveDecision
{
  enum class Action { kDrive, kTurn, kStop } action = Action::kStop;
  double speed = 0.0;        // [m/s] for kDrive
  double heading = 0.0;      // [rad] direction to drive / turn to, base frame
  double corridor_distance = 0.0;  // [m] nearest obstacle in the corridor ahead
};

// target_bearing: direction of the next target in the base frame. standing: |v| ~ 0.
ReactiveDecision decide(const std::vector<PolarReading>& readings, double target_bearing, bool standing,
                        const ReactiveOptions& o);

// Nearest obstacle point inside the corridor of half width w ahead of the robot, rotated by
// `direction` (base frame), as distance along it.
double corridor_distance(const std::vector<Eigen::Vector2d>& base_points, double direction, double half_width);

}  // namespace rgnav::collision_avoidance
