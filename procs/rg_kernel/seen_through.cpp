#include "procs/rg_kernel/seen_through.h"

#include <algorithm>
#include <cmath>

namespace rgnav::rg_kernel {

using Eigen::Vector2d;

namespace {

// A pseudo-angle of the direction q that rises with atan2(q.y, q.x) over (-pi, pi]: the diamond
// angle of -q, in [0, 4).
double pseudo_angle(const Vector2d& q)
{
  const double x = -q.x(), y = -q.y();
  const double s = std::fabs(x) + std::fabs(y);
  if (s <= 0) return 0;
  if (y >= 0) return x >= 0 ? y / s : 1 - x / s;
  return x < 0 ? 2 - y / s : 3 + x / s;
}

}  // namespace

BeamView::BeamView(const geometry::Pose2& region_from_laser, const std::vector<Vector2d>& laser_points, double max_reach)
    : laser_from_region_(region_from_laser.rotation().transpose()), origin_(region_from_laser.translation())
{
  std::vector<double> bearing;
  for (const auto& q : laser_points) {
    const double b = std::atan2(q.y(), q.x());
    if (!bearing.empty() && !(b > bearing.back())) continue;   // beam order: bearings rise
    bearing.push_back(b);
    pseudo_angle_.push_back(pseudo_angle(q));
    range_.push_back(q.norm());
    max_range_ = std::max(max_range_, range_.back());
  }
  max_range_ = std::min(max_range_, max_reach);
  // The beam spacing: the smallest step between valid neighbours (most are neighbouring beams);
  // beams without return between two valid ones are counted by their steps.
  double step = M_PI;
  for (size_t i = 1; i < bearing.size(); ++i) step = std::min(step, bearing[i] - bearing[i - 1]);
  for (const double b : bearing)
    beam_.push_back(static_cast<int32_t>(std::lround((b - (bearing.empty() ? 0.0 : bearing.front())) / step)));
}

bool BeamView::sees_through(const Vector2d& p, const Vector2d& normal, double margin, double min_cos_incidence) const
{
  if (range_.size() < 2) return false;
  const Vector2d from_origin = p - origin_;
  const double d2 = from_origin.squaredNorm(), reach = max_range_ - margin;
  if (d2 < 1e-12 || reach <= 0 || d2 >= reach * reach) return false;   // no beam reaches past it
  const double d = std::sqrt(d2);
  if (normal.squaredNorm() > 0.0 && std::fabs(normal.dot(from_origin)) < min_cos_incidence * d) return false;
  const double a = pseudo_angle(laser_from_region_ * from_origin);
  const auto hi = std::lower_bound(pseudo_angle_.begin(), pseudo_angle_.end(), a);
  if (hi == pseudo_angle_.begin() || hi == pseudo_angle_.end()) return false;
  const size_t i1 = static_cast<size_t>(hi - pseudo_angle_.begin()), i0 = i1 - 1;
  if (beam_[i1] - beam_[i0] != 1) return false;   // a beam without return between: its reach is unknown
  return range_[i0] > d + margin && range_[i1] > d + margin;
}

std::vector<Vector2d> point_normals(const std::vector<Vector2d>& points, double max_gap)
{
  std::vector<Vector2d> out(points.size(), Vector2d::Zero());
  for (size_t i = 0; i < points.size(); ++i) {
    const Vector2d& a = (i > 0 && (points[i - 1] - points[i]).norm() < max_gap) ? points[i - 1] : points[i];
    const Vector2d& b = (i + 1 < points.size() && (points[i + 1] - points[i]).norm() < max_gap) ? points[i + 1] : points[i];
    const Vector2d t = b - a;
    if (t.norm() > 1e-9) out[i] = Vector2d(-t.y(), t.x()).normalized();
  }
  return out;
}

}  // namespace rgnav::rg_kernel
