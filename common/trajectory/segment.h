// One geometric primitive of a trajectory (diss. 5.5.3: "conic, elliptic and straight
// segments, arcs of circles, clothoids"), described by a few parameters: its start pose, its
// arc length and the curvature parameters of its kind. Everything else (poses, headings,
// curvature along it, the closest point to a position) is computed from those.
#pragma once

#include <Eigen/Core>

#include <limits>

#include "geometry/pose2.h"

namespace rgnav::trajectory {

using geometry::Pose2;

enum class Kind : int8_t
{
  kLine = 1,      // curvature 0
  kArc = 2,       // constant curvature kappa0
  kClothoid = 3,  // curvature linear in s from kappa0 to kappa1
  kConic = 4,     // elliptic arc (semi-axes a, b, parametric start angle t0; direction from sign(kappa0))
  kTurn = 5,      // rotation in place by turn_angle (length 0)
};

class Segment
{
 public:
  static Segment line(const Pose2& start, double length);
  static Segment arc(const Pose2& start, double kappa, double length);
  static Segment clothoid(const Pose2& start, double kappa0, double kappa1, double length);
  // Elliptic arc starting at parametric angle t0 of an ellipse with semi-axes a (along the
  // ellipse's x) and b, travelled counter-clockwise if ccw; the ellipse's placement follows
  // from the start pose. Its curvature at the ends is stored in kappa0 / kappa1.
  static Segment conic(const Pose2& start, double a, double b, double t0, bool ccw, double length);
  static Segment turn(const Pose2& start, double angle);

  Kind kind() const { return kind_; }
  const Pose2& start() const { return start_; }
  double length() const { return length_; }
  double kappa0() const { return kappa0_; }
  double kappa1() const { return kappa1_; }
  double semi_a() const { return a_; }
  double semi_b() const { return b_; }
  double ellipse_t0() const { return t0_; }
  double turn_angle() const { return turn_; }
  // Speed limit on this segment [m/s] (infinity: only the robot's limits apply).
  double v_max() const { return v_max_; }
  void set_v_max(double v) { v_max_ = v; }

  // Pose at arc length s in [0, length] (clamped). For a turn: the start pose.
  Pose2 pose_at(double s) const;
  double curvature_at(double s) const;
  // d kappa / d s at s (0 for lines and arcs).
  double sharpness_at(double s) const;
  Pose2 end() const;
  // Heading change over the whole segment [rad], not wrapped.
  double heading_change() const;

 private:
  Segment() = default;
  // Ellipse frame and the parametric angle reached after arc length s.
  double conic_param_at(double s) const;
  Eigen::Vector2d conic_point(double t) const;
  double conic_speed(double t) const;
  double conic_arc_length(double t0, double t1) const;
  double conic_sigma() const { return kappa0_ >= 0 ? 1.0 : -1.0; }

  Kind kind_ = Kind::kLine;
  Pose2 start_;
  double length_ = 0.0;
  double kappa0_ = 0.0;
  double kappa1_ = 0.0;
  double a_ = 0.0, b_ = 0.0, t0_ = 0.0;  // conic
  double psi_ = 0.0;                      // conic: rotation of the ellipse frame
  Eigen::Vector2d center_ = Eigen::Vector2d::Zero();  // conic: ellipse centre
  double turn_ = 0.0;
  double v_max_ = std::numeric_limits<double>::infinity();
};

// Closest point on a segment to a position, searched within [s_lo, s_hi].
struct Projection
{
  double s = 0.0;         // arc length of the closest point on the segment
  double distance = std::numeric_limits<double>::infinity();
  double lateral = 0.0;   // signed: position left of the path is positive
  Pose2 pose;             // pose on the path at s
};
Projection project(const Segment& seg, const Eigen::Vector2d& p, double s_lo, double s_hi);

// Arc length of the ellipse (semi-axes a, b) between parametric angles t0 and t1.
double ellipse_arc_length(double a, double b, double t0, double t1);

}  // namespace rgnav::trajectory
