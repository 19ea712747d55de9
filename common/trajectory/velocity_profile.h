// The speed along a chain under the drive's limits, and the time it takes (diss. 5.5.3: "the
// prediction for the time needed to traverse a chain of trajectory segments is very
// accurate"). The classic two-pass profile: the speed limit at each point (segment limit,
// lateral acceleration v^2 |kappa|, rotational velocity v |kappa|, rotational acceleration
// v^2 |dkappa/ds| on clothoids, allowed step of omega at curvature jumps), then a forward pass
// (accelerate at most a_max) and a backward pass (brake at most a_max). Between samples the
// acceleration is constant, so time and speed are exact for the profile itself. Turns in place
// stop the robot and take a trapezoidal rotation of their own.
#pragma once

#include <limits>
#include <vector>

#include "trajectory/chain.h"

namespace rgnav::trajectory {

struct Limits
{
  double v_max = 0.6;           // [m/s]
  double a_max = 0.5;           // [m/s^2] tangential acceleration and braking
  double a_lat_max = 0.5;       // [m/s^2] v^2 |kappa|
  double omega_max = 1.2;       // [rad/s] v |kappa| and turns in place
  double alpha_max = 1.5;       // [rad/s^2] v^2 |dkappa/ds| and turns in place
  double omega_jump_max = 0.1;  // [rad/s] step of v*kappa allowed at a curvature jump
};

// The reference motion at one instant.
struct ProfileState
{
  double s = 0.0;          // [m] chain arc length
  double v = 0.0;          // [m/s]
  double a = 0.0;          // [m/s^2]
  int turn = -1;           // index of the turn segment being executed, or -1
  double turn_angle = 0.0; // [rad] rotation done so far in that turn
  double omega_turn = 0.0; // [rad/s] its rotational velocity
};

class VelocityProfile
{
 public:
  VelocityProfile() = default;
  // v_start: current speed; v_end: speed at the end (0: stop there). ds: sample spacing.
  static VelocityProfile compute(const Chain& chain, const Limits& limits, double v_start, double v_end,
                                 double ds = 0.02);

  double total_time() const { return knots_.empty() ? 0.0 : knots_.back().t; }
  double length() const { return knots_.empty() ? 0.0 : knots_.back().s; }
  // Reference motion after time t from the start (clamped to [0, total_time]).
  ProfileState at_time(double t) const;
  // Speed when passing s (the first time) and the time to get there.
  double speed_at(double s) const;
  double time_at(double s) const;
  // Speed at the end of segment i (the compact trajectory_segment_t carries it).
  double segment_end_speed(size_t i) const { return segment_end_v_.at(i); }
  // False when v_start was too fast to meet the first limits in time (the profile then
  // brakes at a_max from v_start and overshoots those limits briefly).
  bool feasible() const { return feasible_; }

 private:
  struct Knot
  {
    double t, s, v;
    double a;        // acceleration until the next knot
    int turn = -1;   // this knot starts turns_[turn] (v = 0 throughout)
  };
  struct Turn
  {
    size_t segment;
    double angle, omega_peak, alpha, t_acc, t_total;
  };
  size_t knot_before_time(double t) const;
  size_t knot_before_s(double s) const;

  std::vector<Knot> knots_;
  std::vector<Turn> turns_;
  std::vector<double> segment_end_v_;
  bool feasible_ = true;
};

// Trapezoidal (or triangular) rotation by |angle| under omega_max, alpha_max: its duration.
double turn_duration(double angle, double omega_max, double alpha_max);

}  // namespace rgnav::trajectory
