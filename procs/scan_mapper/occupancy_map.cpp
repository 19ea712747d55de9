#include "scan_mapper/occupancy_map.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::scan_mapper {

template <class F>
void OccupancyGrid::for_each_endpoint(const std::vector<ScanNode>& nodes, const Pose2& base_from_laser,
                                      double max_range, F&& f)
{
  for (const auto& n : nodes) {
    const Pose2 map_from_laser = n.map_from_base * base_from_laser;
    const auto& s = n.scan;
    const double hi = std::min<double>(max_range, s.range_max);
    for (size_t i = 0; i < s.ranges.size(); ++i) {
      const double r = s.ranges[i];
      if (!(r > std::max<double>(0.0, s.range_min)) || !(r < hi)) continue;
      const double a = s.angle_min + static_cast<double>(i) * s.angle_increment;
      f(map_from_laser, map_from_laser * Eigen::Vector2d(r * std::cos(a), r * std::sin(a)));
    }
  }
}

OccupancyGrid OccupancyGrid::build(const std::vector<ScanNode>& nodes, const Pose2& base_from_laser,
                                   const OccupancyOptions& o)
{
  OccupancyGrid g;
  g.o_ = o;
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for_each_endpoint(nodes, base_from_laser, o.max_range_m, [&](const Pose2& origin, const Eigen::Vector2d& p) {
    x0 = std::min({x0, p.x(), origin.x()});
    y0 = std::min({y0, p.y(), origin.y()});
    x1 = std::max({x1, p.x(), origin.x()});
    y1 = std::max({y1, p.y(), origin.y()});
  });
  if (!(x1 >= x0)) return g;
  g.x0_ = x0 - o.margin_m;
  g.y0_ = y0 - o.margin_m;
  g.w_ = static_cast<int>((x1 - x0 + 2 * o.margin_m) / o.resolution_m) + 1;
  g.h_ = static_cast<int>((y1 - y0 + 2 * o.margin_m) / o.resolution_m) + 1;
  g.hits_.assign(static_cast<size_t>(g.w_) * g.h_, 0);
  g.passes_.assign(static_cast<size_t>(g.w_) * g.h_, 0);
  auto bump = [](uint16_t& v) { v = static_cast<uint16_t>(std::min<int>(v + 1, 65535)); };
  for_each_endpoint(nodes, base_from_laser, o.max_range_m, [&](const Pose2& origin, const Eigen::Vector2d& p) {
    // Bresenham from the laser to the end point: cells before the end were seen through.
    int x = g.cell_x(origin.x()), y = g.cell_y(origin.y());
    const int ex = g.cell_x(p.x()), ey = g.cell_y(p.y());
    const int dx = std::abs(ex - x), dy = -std::abs(ey - y), sx = x < ex ? 1 : -1, sy = y < ey ? 1 : -1;
    int err = dx + dy;
    while (x != ex || y != ey) {
      bump(g.passes_[static_cast<size_t>(y) * g.w_ + x]);
      const int e2 = 2 * err;
      if (e2 >= dy) {
        err += dy;
        x += sx;
      }
      if (e2 <= dx) {
        err += dx;
        y += sy;
      }
    }
    bump(g.hits_[static_cast<size_t>(ey) * g.w_ + ex]);
  });
  return g;
}

bool OccupancyGrid::known(int ix, int iy) const
{
  if (ix < 0 || iy < 0 || ix >= w_ || iy >= h_) return false;
  const size_t k = static_cast<size_t>(iy) * w_ + ix;
  return hits_[k] + passes_[k] > 0;
}

bool OccupancyGrid::occupied(int ix, int iy) const
{
  if (!known(ix, iy)) return false;
  const size_t k = static_cast<size_t>(iy) * w_ + ix;
  return hits_[k] >= o_.occupied_ratio * (hits_[k] + passes_[k]);
}

cv::Mat OccupancyGrid::render() const
{
  cv::Mat img(std::max(1, h_), std::max(1, w_), CV_8UC1, cv::Scalar(205));
  for (int y = 0; y < h_; ++y)
    for (int x = 0; x < w_; ++x)
      if (known(x, y)) img.at<uint8_t>(h_ - 1 - y, x) = occupied(x, y) ? 0 : 255;
  return img;
}

double OccupancyGrid::consistency(const std::vector<ScanNode>& nodes, const Pose2& base_from_laser, double tol) const
{
  if (w_ == 0) return 0.0;
  cv::Mat free_mask(h_, w_, CV_8UC1);
  for (int y = 0; y < h_; ++y)
    for (int x = 0; x < w_; ++x) free_mask.at<uint8_t>(y, x) = occupied(x, y) ? 0 : 255;
  cv::Mat dist;
  cv::distanceTransform(free_mask, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  size_t total = 0, good = 0;
  for_each_endpoint(nodes, base_from_laser, o_.max_range_m, [&](const Pose2&, const Eigen::Vector2d& p) {
    const int x = cell_x(p.x()), y = cell_y(p.y());
    ++total;
    if (x >= 0 && y >= 0 && x < w_ && y < h_ && dist.at<float>(y, x) * o_.resolution_m <= tol + 1e-9) ++good;
  });
  return total ? static_cast<double>(good) / static_cast<double>(total) : 0.0;
}

}  // namespace rgnav::scan_mapper
