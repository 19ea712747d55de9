#include "gateway_detector/features.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "geometry/symmetric_eigen2.h"

namespace rgnav::gateway_detector {

Line fit_line(const std::vector<Vec2>& points)
{
  Vec2 mean = Vec2::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : points) cov += (p - mean) * (p - mean).transpose();
  // The normal is the eigenvector of the smallest eigenvalue (orthogonal regression).
  Vec2 n = geometry::symmetric_eigen(cov).vectors.col(0);
  double rho = mean.dot(n);
  if (rho < 0) {
    n = -n;
    rho = -rho;
  }
  return Line{std::atan2(n.y(), n.x()), rho};
}

bool intersect(const Line& a, const Line& b, Vec2* out)
{
  Eigen::Matrix2d m;
  m.row(0) = a.normal().transpose();
  m.row(1) = b.normal().transpose();
  const double det = m.determinant();
  if (std::fabs(det) < 1e-6) return false;
  *out = m.inverse() * Vec2(a.rho, b.rho);
  return true;
}

double ray_range(const Line& line, double bearing)
{
  const double c = Vec2(std::cos(bearing), std::sin(bearing)).dot(line.normal());
  if (std::fabs(c) < 1e-9) return std::numeric_limits<double>::infinity();
  return line.rho / c;
}

double angle_between(const Line& a, const Line& b)
{
  double d = std::fabs(geometry::normalize_angle(a.theta - b.theta));
  if (d > M_PI / 2) d = M_PI - d;
  return d;
}

namespace {

Segment make_segment(const sensors::LaserScan& scan, size_t first, size_t last, const std::vector<size_t>& idx)
{
  std::vector<Vec2> pts;
  for (size_t k = first; k <= last; ++k) pts.push_back(scan.point(idx[k]));
  Segment s;
  s.line = fit_line(pts);
  const Vec2 d = s.line.direction(), f = s.line.foot();
  s.a = f + d * (pts.front() - f).dot(d);
  s.b = f + d * (pts.back() - f).dot(d);
  s.first = idx[first];
  s.last = idx[last];
  s.npoints = static_cast<int>(pts.size());
  return s;
}

// Recursive split of idx[first..last] at the point farthest from the chord.
void split(const sensors::LaserScan& scan, const std::vector<size_t>& idx, size_t first, size_t last,
           const FeatureOptions& o, std::vector<std::pair<size_t, size_t>>* pieces)
{
  if (last - first + 1 < 3) {
    pieces->push_back({first, last});
    return;
  }
  const Vec2 a = scan.point(idx[first]), b = scan.point(idx[last]);
  const Vec2 ab = b - a;
  const double len = ab.norm();
  double best = -1;
  size_t at = first;
  for (size_t k = first + 1; k < last; ++k) {
    const Vec2 p = scan.point(idx[k]) - a;
    const double dist = len > 1e-9 ? std::fabs(ab.x() * p.y() - ab.y() * p.x()) / len : p.norm();
    if (dist > best) {
      best = dist;
      at = k;
    }
  }
  if (best > o.split_distance) {
    split(scan, idx, first, at, o, pieces);
    split(scan, idx, at, last, o, pieces);
  } else {
    pieces->push_back({first, last});
  }
}

}  // namespace

std::vector<Segment> extract_segments(const sensors::LaserScan& scan, const FeatureOptions& o)
{
  // Clusters of consecutive hits without a gap.
  std::vector<std::vector<size_t>> clusters;
  std::vector<size_t> cur;
  for (size_t i = 0; i < scan.size(); ++i) {
    if (!scan.hit(i)) continue;
    if (!cur.empty()) {
      const size_t j = cur.back();
      const double gap = o.cluster_gap + 2.0 * scan.ranges[i] * scan.angle_increment * static_cast<double>(i - j);
      if ((scan.point(i) - scan.point(j)).norm() > gap || i - j > 3) {
        clusters.push_back(std::move(cur));
        cur.clear();
      }
    }
    cur.push_back(i);
  }
  if (!cur.empty()) clusters.push_back(std::move(cur));

  std::vector<Segment> out;
  for (const auto& c : clusters) {
    if (static_cast<int>(c.size()) < o.min_segment_points) continue;
    std::vector<std::pair<size_t, size_t>> pieces;
    split(scan, c, 0, c.size() - 1, o, &pieces);
    for (const auto& [f, l] : pieces) {
      if (static_cast<int>(l - f + 1) < o.min_segment_points) continue;
      Segment s = make_segment(scan, f, l, c);
      if (s.length() >= o.min_segment_length) out.push_back(s);
    }
  }
  return out;
}

std::vector<VirtualLine> group_virtual_lines(const std::vector<Segment>& segments, const FeatureOptions& o)
{
  // Longest segments first: they define the line best.
  std::vector<int> order(segments.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return segments[a].length() > segments[b].length(); });

  std::vector<VirtualLine> lines;
  for (int si : order) {
    const Segment& s = segments[si];
    VirtualLine* home = nullptr;
    for (auto& vl : lines) {
      if (angle_between(vl.line, s.line) > o.virtual_line_angle) continue;
      if (std::fabs(vl.line.signed_distance(s.a)) > o.virtual_line_distance) continue;
      if (std::fabs(vl.line.signed_distance(s.b)) > o.virtual_line_distance) continue;
      home = &vl;
      break;
    }
    if (!home) {
      lines.push_back(VirtualLine{});
      home = &lines.back();
    }
    home->segments.push_back(si);
    home->support += s.length();
    // Refit from the segment end points weighted by length (cheap, and the segments are
    // regression lines already).
    std::vector<Vec2> pts;
    for (int k : home->segments) {
      const Segment& m = segments[k];
      const int n = std::max(2, static_cast<int>(std::ceil(m.length() / 0.1)));
      for (int j = 0; j <= n; ++j) pts.push_back(m.a + (m.b - m.a) * (static_cast<double>(j) / n));
    }
    home->line = fit_line(pts);
  }
  for (auto& vl : lines) {
    const Vec2 d = vl.line.direction(), f = vl.line.foot();
    vl.t_min = std::numeric_limits<double>::infinity();
    vl.t_max = -vl.t_min;
    for (int k : vl.segments) {
      for (const Vec2& p : {segments[k].a, segments[k].b}) {
        const double t = (p - f).dot(d);
        vl.t_min = std::min(vl.t_min, t);
        vl.t_max = std::max(vl.t_max, t);
      }
    }
  }
  return lines;
}

std::vector<DepthSingularity> depth_singularities(const sensors::LaserScan& scan, double jump)
{
  std::vector<DepthSingularity> out;
  auto range = [&](size_t i) { return scan.no_return(i) ? scan.range_max : scan.ranges[i]; };
  for (size_t i = 0; i < scan.size(); ++i) {
    if (!scan.hit(i)) continue;
    const double d = scan.ranges[i];
    for (int side : {-1, +1}) {
      if ((side < 0 && i == 0) || (side > 0 && i + 1 >= scan.size())) continue;
      const size_t j = side < 0 ? i - 1 : i + 1;
      if (scan.invalid(j)) continue;
      if (range(j) - d > jump) out.push_back({i, scan.point(i), side});
    }
  }
  return out;
}

ScanFeatures extract_features(const sensors::LaserScan& scan, const FeatureOptions& o)
{
  ScanFeatures f;
  f.segments = extract_segments(scan, o);
  f.virtual_lines = group_virtual_lines(f.segments, o);
  f.singularities = depth_singularities(scan, o.depth_jump);
  return f;
}

}  // namespace rgnav::gateway_detector
