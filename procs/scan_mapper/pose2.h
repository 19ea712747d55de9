// Planar rigid transforms, named a_from_b so that a_from_b * b_from_c reads right.
#pragma once

#include <Eigen/Core>

#include <cmath>

namespace rgnav::scan_mapper {

inline double normalize_angle(double a) { return std::remainder(a, 2.0 * M_PI); }

struct Pose2
{
  double x = 0.0, y = 0.0, theta = 0.0;

  Pose2 operator*(const Pose2& b) const
  {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * b.x - s * b.y, y + s * b.x + c * b.y, normalize_angle(theta + b.theta)};
  }
  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const
  {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y()};
  }
  Pose2 inverse() const
  {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-c * x - s * y, s * x - c * y, normalize_angle(-theta)};
  }
  Eigen::Vector3d vector() const { return {x, y, theta}; }
  static Pose2 from(const Eigen::Vector3d& v) { return {v.x(), v.y(), normalize_angle(v.z())}; }
  double translation_norm() const { return std::hypot(x, y); }
};

// a_from_b given map_from_a and map_from_b.
inline Pose2 between(const Pose2& map_from_a, const Pose2& map_from_b) { return map_from_a.inverse() * map_from_b; }

// Linear interpolation of poses (shortest way round in theta), s in [0, 1].
inline Pose2 interpolate(const Pose2& a, const Pose2& b, double s)
{
  return {a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), normalize_angle(a.theta + s * normalize_angle(b.theta - a.theta))};
}

}  // namespace rgnav::scan_mapper
