// The tracking law of the low-level drive: Kanayama, Kimura, Miyazaki, Noguchi, "A stable
// tracking control method for an autonomous mobile robot", ICRA 1990 (the "Lyapunov feedback
// controller" of diss. 5.5.3). For a unicycle / synchro drive following a reference pose
// q_r = (x_r, y_r, theta_r) that moves with (v_r, omega_r), the error in the robot frame is
//
//   e = (e_x, e_y, e_theta) = R(-theta) (x_r - x, y_r - y), theta_r - theta
//
// and the commanded velocities are
//
//   v     = v_r cos(e_theta) + k_x e_x
//   omega = omega_r + v_r (k_y e_y + k_theta sin(e_theta)).
//
// With the Lyapunov function
//
//   V = (e_x^2 + e_y^2) / 2 + (1 - cos(e_theta)) / k_y          (V >= 0, V = 0 iff e = 0)
//
// the closed loop gives dV/dt = -k_x e_x^2 - v_r k_theta sin^2(e_theta) / k_y <= 0, so the
// reference is asymptotically tracked for k_x > 0, k_y > 0, k_theta > 0 and v_r > 0 (v_r,
// omega_r continuous and bounded). Linearised about e = 0 the lateral error obeys, per metre
// travelled, e_y'' + k_theta e_y' + k_y e_y = 0: critical damping at k_theta = 2 sqrt(k_y),
// with a settling distance of ~4 / sqrt(k_y) — the gains are chosen that way (lld.yaml).
// When v_r = 0 (turns in place) the lateral and heading terms vanish; a plain heading
// feedback k_turn sin(e_theta) then keeps the rotation on its profile.
#pragma once

#include "geometry/pose2.h"

namespace rgnav::lld {

struct TrackingGains
{
  double k_x = 2.0;       // [1/s] along-track
  double k_y = 25.0;      // [1/m^2] cross-track
  double k_theta = 10.0;  // [1/m] heading (2 sqrt(k_y): critically damped)
  double k_turn = 3.0;    // [1/s] heading feedback while turning in place
};

struct TrackingError
{
  double e_x = 0.0;      // [m] reference ahead of the robot: positive
  double e_y = 0.0;      // [m] reference left of the robot: positive
  double e_theta = 0.0;  // [rad] reference heading minus robot heading, wrapped
};

struct VelocityCommand
{
  double v = 0.0;      // [m/s]
  double omega = 0.0;  // [rad/s]
};

TrackingError tracking_error(const geometry::Pose2& reference, const geometry::Pose2& robot);

// The law above; valid gains (all > 0) are checked where the options are loaded.
VelocityCommand kanayama(const TrackingError& e, double v_r, double omega_r, const TrackingGains& g);

// The Lyapunov function V(e) (tests check that it decreases along closed-loop motion).
double lyapunov(const TrackingError& e, const TrackingGains& g);

}  // namespace rgnav::lld
