#include "route_checks.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace rgnav::plan_eval {

using Eigen::Vector2d;

double polyline_length(const std::vector<Vector2d>& p)
{
  double l = 0;
  for (size_t k = 1; k < p.size(); ++k) l += (p[k] - p[k - 1]).norm();
  return l;
}

CheckedRoute check_route(const rgmap::RgMap& map, const planner::Route& route, const RegionPoint& start, const RegionPoint& goal,
                         double adapt_distance)
{
  CheckedRoute c;
  const auto& legs = route.legs;
  if (legs.empty()) {
    c.defect = "no legs";
    return c;
  }
  double sum = 0;
  for (size_t i = 0; i < legs.size(); ++i) {
    const auto& leg = legs[i];
    const auto* r = map.region(leg.region_id);
    if (!r || leg.points.empty()) {
      c.defect = "leg " + std::to_string(i) + " in unknown region " + std::to_string(leg.region_id) + " or without points";
      return c;
    }
    const double l = polyline_length(leg.points);
    if (std::abs(l - leg.length) > 1e-3 + 1e-3 * l && c.defect.empty())
      c.defect = "leg " + std::to_string(i) + " length " + std::to_string(leg.length) + " but its points make " + std::to_string(l);
    sum += l;
    for (const auto& p : leg.points) c.map_points.push_back(r->map_from_region * p);
    if (i + 1 < legs.size()) {
      const double gap = (leg.this_from_next * legs[i + 1].points.front() - leg.points.back()).norm();
      c.join_gap_max = std::max(c.join_gap_max, gap);
      sum += gap;
      if (gap > 0.3 && c.defect.empty())
        c.defect = "legs " + std::to_string(i) + "/" + std::to_string(i + 1) + " meet " + std::to_string(gap) + " m apart";
    }
  }
  c.length = sum;
  if (legs.front().region_id != start.region && c.defect.empty()) c.defect = "first leg not in the start region";
  if (legs.back().region_id != goal.region && c.defect.empty()) c.defect = "last leg not in the goal region";
  if ((legs.front().points.front() - start.point).norm() > adapt_distance + 0.05 && c.defect.empty())
    c.defect = "route starts " + std::to_string((legs.front().points.front() - start.point).norm()) + " m from the start";
  if ((legs.back().points.back() - goal.point).norm() > adapt_distance + 0.05 && c.defect.empty())
    c.defect = "route ends " + std::to_string((legs.back().points.back() - goal.point).norm()) + " m from the goal";
  if (std::abs(route.length - sum) > 0.01 * sum + 0.05 && c.defect.empty())
    c.defect = "route length " + std::to_string(route.length) + " but its legs make " + std::to_string(sum);
  return c;
}

SampledClearance sample_clearance(const ConfigSpace& space, const std::vector<Vector2d>& pts, double end_m)
{
  SampledClearance s;
  const double step = space.grid().resolution;
  const double total = polyline_length(pts);
  double along = 0, sum = 0;
  int n = 0;
  for (size_t k = 1; k < pts.size(); ++k) {
    const double l = (pts[k] - pts[k - 1]).norm();
    const int m = std::max(1, static_cast<int>(std::ceil(l / step)));
    for (int i = 0; i < m; ++i) {
      const double f = static_cast<double>(i) / m;
      const double c = space.clearance_at(pts[k - 1] + f * (pts[k] - pts[k - 1]));
      const double at = along + f * l;
      s.min = std::min(s.min, c);
      if (at > end_m && at < total - end_m && c < s.interior_min) {
        s.interior_min = c;
        s.interior_min_at = pts[k - 1] + f * (pts[k] - pts[k - 1]);
      }
      sum += c;
      ++n;
    }
    along += l;
  }
  if (!pts.empty()) {
    const double c = space.clearance_at(pts.back());
    s.min = std::min(s.min, c);
    sum += c;
    ++n;
  }
  s.mean = n ? sum / n : NAN;
  return s;
}

void draw_routes(const ConfigSpace& space, const std::vector<DrawnPair>& drawn, const std::string& path)
{
  const auto& g = space.grid();
  cv::Mat img(g.height, g.width, CV_8UC3);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const Cell c(x, y);
      const uint8_t v = g.at(c);
      cv::Vec3b col = v == OccupancyGrid::kOccupied ? cv::Vec3b(0, 0, 0)
                      : v == OccupancyGrid::kUnknown ? cv::Vec3b(180, 180, 180)
                      : space.free(c)                ? cv::Vec3b(255, 255, 255)
                                                     : cv::Vec3b(225, 225, 235);
      img.at<cv::Vec3b>(g.height - 1 - y, x) = col;
    }
  const auto px = [&](const Vector2d& p) {
    const Vector2d q = (p - g.origin) / g.resolution;
    return cv::Point(static_cast<int>(q.x()), g.height - 1 - static_cast<int>(q.y()));
  };
  const auto poly = [&](const std::vector<Vector2d>& pts, const cv::Scalar& col, int width) {
    for (size_t k = 1; k < pts.size(); ++k) cv::line(img, px(pts[k - 1]), px(pts[k]), col, width, cv::LINE_AA);
  };
  for (const auto& d : drawn) {
    poly(d.reference, cv::Scalar(200, 90, 0), 1);   // BGR: blue
    poly(d.route, cv::Scalar(0, 0, 220), 2);        // red
    if (!d.route.empty()) {
      cv::circle(img, px(d.route.front()), 5, cv::Scalar(0, 160, 0), cv::FILLED);
      cv::circle(img, px(d.route.back()), 5, cv::Scalar(160, 0, 160), cv::FILLED);
    }
  }
  cv::imwrite(path, img);
}

}  // namespace rgnav::plan_eval
