#include "collision_avoidance/local_grid.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace rgnav::collision_avoidance {

namespace {

// Straight leg a -> b keeps `clearance` from the map's points (sampled every 5 cm); where the
// start is already closer than that, the leg may not get closer than the start is.
bool leg_free(const LocalMap& map, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double clearance,
              double start_clearance)
{
  const double len = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(len / 0.05)));
  for (int i = 1; i <= n; ++i) {
    const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(i) / n);
    const double need = std::min(clearance, start_clearance);
    if (map.clearance(p, clearance) < need - 1e-9) return false;
  }
  return true;
}

}  // namespace

LocalGrid::LocalGrid(const LocalMap& map, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double cell)
    : lo_(lo), cell_(cell)
{
  w_ = static_cast<int>(std::ceil((hi.x() - lo.x()) / cell));
  h_ = static_cast<int>(std::ceil((hi.y() - lo.y()) / cell));
  // Obstacles are the zero pixels of the distance transform's input.
  cv::Mat free_img(h_, w_, CV_8UC1, cv::Scalar(255));
  for (const auto& p : map.points()) {
    if (p.x() < lo.x() || p.y() < lo.y() || p.x() >= hi.x() || p.y() >= hi.y()) continue;
    const Eigen::Vector2i c = cell_of(p);
    free_img.at<uint8_t>(c.y(), c.x()) = 0;
  }
  cv::distanceTransform(free_img, dist_, cv::DIST_L2, cv::DIST_MASK_PRECISE);

  seen_ = cv::Mat(h_, w_, CV_8UC1, cv::Scalar(0));
  cone_ = cv::Mat(h_, w_, CV_8UC1, cv::Scalar(0));
  std::vector<const ScanPoints*> views;
  for (const auto& sc : map.views()) views.push_back(&sc);
  for (const auto& sc : map.scans()) views.push_back(&sc);
  for (const ScanPoints* view : views) {
    const ScanPoints& sc = *view;
    if (sc.outline.empty()) continue;
    auto px = [&](const Eigen::Vector2d& base) {
      const Eigen::Vector2d p = sc.odom_from_base * base;
      return cv::Point(static_cast<int>(std::floor((p.x() - lo.x()) / cell)),
                       static_cast<int>(std::floor((p.y() - lo.y()) / cell)));
    };
    std::vector<cv::Point> vis{px(sc.laser_origin)}, fov{px(sc.laser_origin)};
    const double far = hi.x() - lo.x() + hi.y() - lo.y();
    for (const auto& e : sc.outline) {
      vis.push_back(px(e));
      const Eigen::Vector2d d = e - sc.laser_origin;
      if (d.norm() > 1e-6) fov.push_back(px(sc.laser_origin + d.normalized() * far));
    }
    cv::fillPoly(cone_, std::vector<std::vector<cv::Point>>{fov}, cv::Scalar(255));
    cv::fillPoly(seen_, std::vector<std::vector<cv::Point>>{vis}, cv::Scalar(255));
  }
}

Eigen::Vector2i LocalGrid::cell_of(const Eigen::Vector2d& p) const
{
  return Eigen::Vector2i(std::clamp(static_cast<int>(std::floor((p.x() - lo_.x()) / cell_)), 0, w_ - 1),
                         std::clamp(static_cast<int>(std::floor((p.y() - lo_.y()) / cell_)), 0, h_ - 1));
}

Eigen::Vector2d LocalGrid::centre(int x, int y) const
{
  return Eigen::Vector2d(lo_.x() + (x + 0.5) * cell_, lo_.y() + (y + 0.5) * cell_);
}

double LocalGrid::clearance(int x, int y) const
{
  return std::max(0.0, dist_.at<float>(y, x) * cell_ - 0.71 * cell_);
}

std::vector<Eigen::Vector2d> line_of_sight_corners(const LocalMap& map, const std::vector<Eigen::Vector2d>& cells,
                                                   double clearance)
{
  // From each corner, the farthest path point reachable in a straight free leg.
  std::vector<Eigen::Vector2d> corners;
  size_t i = 0;
  while (i + 1 < cells.size()) {
    size_t best = i + 1;  // the grid's own step is trusted when nothing longer is free
    const double sc = i == 0 ? map.clearance(cells.front(), clearance) : clearance;
    // Growing the leg until it first touches: linear in the path length per corner.
    for (size_t j = i + 2; j < cells.size() && leg_free(map, cells[i], cells[j], clearance, sc); ++j) best = j;
    corners.push_back(cells[best]);
    i = best;
  }
  return corners;
}

}  // namespace rgnav::collision_avoidance
