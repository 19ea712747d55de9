#include "vision/object_rectangles.h"

#include <algorithm>
#include <cmath>

namespace rgnav::vision {

ObjectRectangle to_object(const Rectangle3d& cam, const Eigen::Isometry3d& base_from_camera, const KindOptions& o,
                          double grey_inside)
{
  ObjectRectangle r;
  for (int i = 0; i < 4; ++i) r.corners[i] = base_from_camera * cam.corners[i];
  r.normal = (base_from_camera.linear() * cam.normal).normalized();
  // Counter-clockwise seen from the front (from where the normal points).
  const Eigen::Vector3d turn = (r.corners[1] - r.corners[0]).cross(r.corners[2] - r.corners[1]);
  if (turn.dot(r.normal) < 0.0) std::swap(r.corners[1], r.corners[3]);
  const Eigen::Vector3d a = r.corners[1] - r.corners[0], b = r.corners[2] - r.corners[1];
  const double side_a = 0.5 * (a.norm() + (r.corners[2] - r.corners[3]).norm());
  const double side_b = 0.5 * (b.norm() + (r.corners[3] - r.corners[0]).norm());
  const bool a_vertical = std::fabs(a.normalized().z()) > std::fabs(b.normalized().z());
  r.height = a_vertical ? side_a : side_b;
  r.width = a_vertical ? side_b : side_a;
  const double bottom = std::min({r.corners[0].z(), r.corners[1].z(), r.corners[2].z(), r.corners[3].z()});
  const double top = std::max({r.corners[0].z(), r.corners[1].z(), r.corners[2].z(), r.corners[3].z()});
  constexpr int8_t kUnknown = 0, kDoor = 1, kWhiteboard = 2, kMonitor = 3, kTable = 4;  // rectangle3d_t::KIND_*
  const auto within = [](double x, double lo, double hi) { return x >= lo && x <= hi; };
  const bool upright = std::fabs(r.normal.z()) <= o.upright_max_normal_z;
  const bool white = grey_inside >= o.whiteboard_min_grey;
  r.kind = kUnknown;
  if (upright && within(r.width, o.door_min_width, o.door_max_width) && within(r.height, o.door_min_height, o.door_max_height) &&
      bottom <= o.door_max_bottom)
    r.kind = kDoor;
  else if (std::fabs(r.normal.z()) >= o.level_min_normal_z && bottom >= o.table_min_z && top <= o.table_max_z)
    r.kind = kTable;
  else if (upright && white && bottom >= o.wall_min_bottom && within(r.width, o.whiteboard_min_width, o.whiteboard_max_width) &&
           within(r.height, o.whiteboard_min_height, o.whiteboard_max_height))
    r.kind = kWhiteboard;
  else if (upright && !white && r.width >= r.height && within(bottom, std::max(o.wall_min_bottom, o.table_min_z), o.monitor_max_bottom) &&
           within(r.width, o.monitor_min_width, o.monitor_max_width) && within(r.height, o.monitor_min_height, o.monitor_max_height))
    r.kind = kMonitor;
  return r;
}

}  // namespace rgnav::vision
