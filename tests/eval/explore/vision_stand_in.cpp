#include "vision_stand_in.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "geometry/segment2.h"

namespace rgnav::explore_eval {

using Eigen::Vector2d;

VisionStandIn::VisionStandIn(const sim::World& world, const VisionStandInOptions& options) : options_(options)
{
  std::vector<sim::Box> solids = world.boxes;
  for (const auto& t : world.tables)
    for (const auto& part : t.parts()) solids.push_back(part);
  for (const auto& b : solids) {
    const bool laser_sees = b.z_min <= options_.laser_height && b.z_max >= options_.laser_height;
    if (laser_sees || b.z_max < options_.min_height || b.z_min > options_.max_height) continue;
    const double top = std::min(b.z_max, options_.max_height);
    const int nx = std::max(1, static_cast<int>(std::ceil(b.size.x() / options_.sample_m)));
    const int ny = std::max(1, static_cast<int>(std::ceil(b.size.y() / options_.sample_m)));
    const Eigen::Rotation2Dd rot(b.yaw);
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j) {
        const Vector2d local((i + 0.5) / nx * b.size.x() - 0.5 * b.size.x(), (j + 0.5) / ny * b.size.y() - 0.5 * b.size.y());
        samples_.push_back({b.center + rot * local, top, false});
      }
  }
  for (const auto& w : world.walls)
    if (w.z_max > options_.laser_height) walls_.emplace_back(w.a, w.b);
}

bool VisionStandIn::wall_between(const Vector2d& a, const Vector2d& b) const
{
  return std::any_of(walls_.begin(), walls_.end(),
                     [&](const auto& w) { return geometry::segments_cross(a, b, w.first, w.second); });
}

size_t VisionStandIn::seen() const
{
  return static_cast<size_t>(std::count_if(samples_.begin(), samples_.end(), [](const Sample& s) { return s.seen; }));
}

std::vector<Vector2d> VisionStandIn::update(double t_s, const geometry::Pose2& world_from_base,
                                            const geometry::Pose2& odom_from_base)
{
  next_s_ = t_s + options_.period_s;
  const Vector2d robot = world_from_base.translation();
  const double heading = world_from_base.theta();
  for (auto& s : samples_) {
    if (s.seen) continue;
    const Vector2d d = s.at - robot;
    const double range = d.norm();
    if (range > options_.range_m || range < 1e-3) continue;
    if (std::abs(geometry::normalize_angle(std::atan2(d.y(), d.x()) - heading)) > 0.5 * options_.fov_h) continue;
    if (std::abs(std::atan2(s.top - options_.head_height, range)) > 0.5 * options_.fov_v) continue;
    if (wall_between(robot, s.at)) continue;
    s.seen = true;
  }
  const geometry::Pose2 odom_from_world = odom_from_base * world_from_base.inverse();
  std::vector<Vector2d> points;
  for (const auto& s : samples_)
    if (s.seen && (s.at - robot).cwiseAbs().maxCoeff() <= options_.grid_half_m) points.push_back(odom_from_world * s.at);
  return points;
}

}  // namespace rgnav::explore_eval
