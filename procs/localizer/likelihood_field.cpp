#include "localizer/likelihood_field.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "geometry/segment2.h"

namespace rgnav::localizer {

namespace {
constexpr int kExactBand = 2;   // [cells] around a line the distance is computed from the segment
}

LikelihoodField::LikelihoodField(const std::vector<rgmap::LineSegment>& segments, double resolution,
                                 double max_distance, double margin,
                                 const std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& clip)
    : inv_resolution_(1.0 / resolution), max_distance_(static_cast<float>(max_distance))
{
  if (segments.empty()) return;
  Eigen::Vector2d lo = segments.front().a, hi = segments.front().a;
  for (const auto& s : segments) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  }
  lo -= Eigen::Vector2d(margin, margin);
  hi += Eigen::Vector2d(margin, margin);
  if (clip) {
    lo = lo.cwiseMax(clip->first);
    hi = hi.cwiseMin(clip->second);
    if (lo.x() >= hi.x() || lo.y() >= hi.y()) return;
  }
  origin_ = lo;
  const int cols = static_cast<int>(std::ceil((hi.x() - lo.x()) * inv_resolution_)) + 1;
  const int rows = static_cast<int>(std::ceil((hi.y() - lo.y()) * inv_resolution_)) + 1;
  // distanceTransform measures to the nearest zero pixel: lines are drawn as 0 on 255.
  cv::Mat lines(rows, cols, CV_8U, cv::Scalar(255));
  const auto pixel = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>(std::floor((p.x() - origin_.x()) * inv_resolution_)),
                     static_cast<int>(std::floor((p.y() - origin_.y()) * inv_resolution_)));
  };
  for (const auto& s : segments) cv::line(lines, pixel(s.a), pixel(s.b), cv::Scalar(0), 1, cv::LINE_8);
  cv::distanceTransform(lines, distance_, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  // Pixels -> metres. The distance is to the centre of the nearest line pixel, which lies up to
  // half a cell off the line: the exact distance of each cell centre near a line (within two
  // cells) is computed from the segments instead.
  distance_ *= resolution;
  const float band = static_cast<float>(kExactBand * resolution);
  for (int cy = 0; cy < distance_.rows; ++cy) {
    float* row = distance_.ptr<float>(cy);
    for (int cx = 0; cx < distance_.cols; ++cx)
      if (row[cx] < band) row[cx] = band;   // recomputed exactly below
  }
  for (const auto& s : segments) exact_near(s, resolution);
  cv::min(distance_, max_distance, distance_);
}

void LikelihoodField::exact_near(const rgmap::LineSegment& s, double resolution)
{
  const Eigen::Vector2d lo = s.a.cwiseMin(s.b), hi = s.a.cwiseMax(s.b);
  const int x0 = std::max(0, static_cast<int>(std::floor((lo.x() - origin_.x()) * inv_resolution_)) - kExactBand);
  const int y0 = std::max(0, static_cast<int>(std::floor((lo.y() - origin_.y()) * inv_resolution_)) - kExactBand);
  const int x1 = std::min(distance_.cols - 1, static_cast<int>(std::floor((hi.x() - origin_.x()) * inv_resolution_)) + kExactBand);
  const int y1 = std::min(distance_.rows - 1, static_cast<int>(std::floor((hi.y() - origin_.y()) * inv_resolution_)) + kExactBand);
  for (int cy = y0; cy <= y1; ++cy)
    for (int cx = x0; cx <= x1; ++cx) {
      const Eigen::Vector2d c = origin_ + resolution * Eigen::Vector2d(cx + 0.5, cy + 0.5);
      const float d = static_cast<float>(geometry::point_segment_distance(c, s.a, s.b));
      float& cell = distance_.at<float>(cy, cx);
      cell = std::min(cell, d);
    }
}

}  // namespace rgnav::localizer
