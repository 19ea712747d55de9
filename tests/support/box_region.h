// A hand-made region for tests of what reads RG maps (planner, explorer): the map frame shifted
// to `lo`, walls (map frame) as its line map, and freespace at `resolution` over the box
// [lo, hi] (map frame), less what `blocked` says of a cell's centre (map frame).
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "geometry/pose2.h"
#include "rgmap/rg_map.h"

namespace rgnav::testing {

using BoxWall = std::pair<Eigen::Vector2d, Eigen::Vector2d>;

inline rgmap::Region& add_box_region(rgmap::RgMap* map, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                     const std::vector<BoxWall>& walls, double resolution, int64_t utime,
                                     const std::function<bool(const Eigen::Vector2d&)>& blocked = {})
{
  const geometry::Pose2 map_from_region(lo, 0.0);
  rgmap::Region& r = map->add_region(map_from_region, utime);
  for (const auto& [a, b] : walls) {
    rgmap::LineSegment s;
    s.a = map_from_region.inverse() * a;
    s.b = map_from_region.inverse() * b;
    r.segments.push_back(s);
  }
  const Eigen::Vector2d size = hi - lo;
  const int w = static_cast<int>(std::lround(size.x() / resolution));
  const int h = static_cast<int>(std::lround(size.y() / resolution));
  r.freespace = rgmap::FreespaceBitmap(resolution, geometry::Pose2(0, 0, 0), w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Eigen::Vector2d c = lo + Eigen::Vector2d((x + 0.5) * resolution, (y + 0.5) * resolution);
      r.freespace.set_free(x, y, !blocked || !blocked(c));
    }
  r.bbox_min = Eigen::Vector2d::Zero();
  r.bbox_max = size;
  return r;
}

}  // namespace rgnav::testing
