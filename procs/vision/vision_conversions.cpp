#include "vision/vision_conversions.h"

#include "msg/conversions.h"

namespace rgnav::vision {

obstacle_grid_t to_msg(const ObstacleGrid& g)
{
  obstacle_grid_t m;
  m.utime = g.utime;
  m.odom_from_grid = msg::to_msg(g.odom_from_grid);
  m.resolution = static_cast<float>(g.resolution);
  m.width = g.width;
  m.height = g.height;
  m.ncells = static_cast<int32_t>(g.cells.size());
  m.cells = g.cells;
  m.min_height = static_cast<float>(g.min_height);
  m.max_height = static_cast<float>(g.max_height);
  return m;
}

ObstacleGrid from_msg(const obstacle_grid_t& m)
{
  ObstacleGrid g;
  g.utime = m.utime;
  g.odom_from_grid = msg::to_pose2(m.odom_from_grid);
  g.resolution = m.resolution;
  g.width = m.width;
  g.height = m.height;
  g.cells = m.cells;
  g.min_height = m.min_height;
  g.max_height = m.max_height;
  return g;
}

objects3d_t to_msg(const std::vector<ObjectRectangle>& rectangles, int64_t utime, int64_t frame_id, int64_t scan_id,
                   const geometry::Pose2& odom_from_base)
{
  objects3d_t m{};
  m.utime = utime;
  m.frame_id = frame_id;
  m.scan_id = scan_id;
  m.odom_from_base = msg::to_msg(odom_from_base);
  m.nrectangles = static_cast<int32_t>(rectangles.size());
  m.rectangles.resize(rectangles.size());
  for (size_t k = 0; k < rectangles.size(); ++k) {
    const ObjectRectangle& r = rectangles[k];
    rectangle3d_t& x = m.rectangles[k];
    x.id = static_cast<int64_t>(k) + 1;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 3; ++j) x.corners[i][j] = r.corners[static_cast<size_t>(i)](j);
    for (int j = 0; j < 3; ++j) x.normal[j] = r.normal(j);
    x.width = r.width;
    x.height = r.height;
    x.confidence = 0.5f;
    x.kind = r.kind;
  }
  return m;
}

}  // namespace rgnav::vision
