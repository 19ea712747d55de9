// Rigid transforms in the plane. Named by what they map: `world_from_robot` takes points in
// the robot frame to the world frame, so `a_from_b * b_from_c` reads right and yields a_from_c.
#pragma once

#include <Eigen/Core>

#include <cmath>

namespace rgnav::geometry {

// Wraps an angle to (-pi, pi].
inline double normalize_angle(double a)
{
  a = std::remainder(a, 2.0 * M_PI);
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}

class Pose2
{
 public:
  Pose2() = default;
  Pose2(double x, double y, double theta) : t_(x, y), theta_(normalize_angle(theta)) {}
  Pose2(const Eigen::Vector2d& t, double theta) : t_(t), theta_(normalize_angle(theta)) {}

  double x() const { return t_.x(); }
  double y() const { return t_.y(); }
  double theta() const { return theta_; }
  const Eigen::Vector2d& translation() const { return t_; }

  Eigen::Matrix2d rotation() const
  {
    const double c = std::cos(theta_), s = std::sin(theta_);
    Eigen::Matrix2d r;
    r << c, -s, s, c;
    return r;
  }

  Pose2 operator*(const Pose2& b) const { return Pose2(t_ + rotation() * b.t_, theta_ + b.theta_); }
  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const { return t_ + rotation() * p; }
  Pose2 inverse() const { return Pose2(-(rotation().transpose() * t_), -theta_); }

  // The motion from this pose to `b`, in this pose's frame: this->inverse() * b.
  Pose2 between(const Pose2& b) const { return inverse() * b; }

 private:
  Eigen::Vector2d t_ = Eigen::Vector2d::Zero();
  double theta_ = 0.0;
};

}  // namespace rgnav::geometry
