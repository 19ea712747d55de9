#include "vision/image_quadrangles.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "geometry/segment2.h"

namespace rgnav::vision {
namespace {

using Eigen::Vector2d;

double length(const ImageSegment& s) { return (s.b - s.a).norm(); }

// The smaller of the two angles between the segments' lines [rad], 0..pi/2.
double line_angle(const ImageSegment& s, const ImageSegment& t)
{
  const Vector2d u = (s.b - s.a).normalized(), v = (t.b - t.a).normalized();
  return std::acos(std::min(1.0, std::fabs(u.dot(v))));
}

// Where the lines of s and t meet (they are not parallel: the grouping asked for an angle).
Vector2d meet(const ImageSegment& s, const ImageSegment& t)
{
  const auto hit = geometry::ray_meets_line(s.a, s.b - s.a, t.a, t.b, 1e-12);
  return hit ? Vector2d(s.a + (s.b - s.a) * hit->along_ray) : Vector2d(0.5 * (s.b + t.a));
}

double area(const Quadrangle& q)
{
  double a = 0.0;
  for (int i = 0; i < 4; ++i) a += geometry::cross(q[i], q[(i + 1) % 4]);
  return 0.5 * std::fabs(a);
}

bool convex(const Quadrangle& q)
{
  int sign = 0;
  for (int i = 0; i < 4; ++i) {
    const double c = geometry::cross(q[(i + 1) % 4] - q[i], q[(i + 2) % 4] - q[(i + 1) % 4]);
    const int s = c > 0 ? 1 : -1;
    if (sign == 0) sign = s;
    if (s != sign || std::fabs(c) < 1e-9) return false;
  }
  return true;
}

}  // namespace

std::vector<ImageSegment> detect_segments(const cv::Mat& gray)
{
  std::vector<cv::Vec4f> lines;
  cv::createLineSegmentDetector(cv::LSD_REFINE_STD)->detect(gray, lines);
  std::vector<ImageSegment> out;
  out.reserve(lines.size());
  for (const auto& l : lines) out.push_back({Vector2d(l[0], l[1]), Vector2d(l[2], l[3])});
  return out;
}

std::vector<ImageSegment> merge_segments(std::vector<ImageSegment> segs, const QuadrangleOptions& o)
{
  // The angle test as a cosine (no acos per pair: merging compares every pair, and the
  // segments of a textured view run to a thousand).
  const double min_cos = std::cos(o.merge_angle_deg * M_PI / 180.0);
  std::vector<Vector2d> dir(segs.size());
  std::vector<double> len(segs.size());
  std::vector<char> gone(segs.size(), 0);
  const auto update = [&](size_t i) {
    len[i] = length(segs[i]);
    dir[i] = len[i] > 1e-9 ? Vector2d((segs[i].b - segs[i].a) / len[i]) : Vector2d::Zero();
  };
  for (size_t i = 0; i < segs.size(); ++i) update(i);
  // Passes until nothing merges: a merged segment may now reach a third one. Within a pass a
  // segment that grew is compared with all the others again.
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t i = 0; i < segs.size(); ++i) {
      if (gone[i] || len[i] < 1e-9) continue;
      for (size_t j = 0; j < segs.size(); ++j) {
        if (j == i || gone[j] || len[j] < 1e-9) continue;
        const Vector2d &us = dir[i], &ut = dir[j];
        // alpha_max, or what the shorter one's direction is good for: its ends are found to
        // about D_L, so a 20 px piece of an edge leans by up to atan(D_L / 20 px) = 6 degrees.
        const double cos_ij = std::fabs(us.dot(ut)), shorter = std::min(len[i], len[j]);
        if (cos_ij < min_cos && cos_ij < shorter / std::hypot(o.merge_distance_px, shorter)) continue;
        const ImageSegment &s = segs[i], &t = segs[j];
        // D_L: mean distance of each one's end points from the other's line.
        const double dl = 0.25 * (std::fabs(geometry::cross(us, t.a - s.a)) + std::fabs(geometry::cross(us, t.b - s.a)) +
                                  std::fabs(geometry::cross(ut, s.a - t.a)) + std::fabs(geometry::cross(ut, s.b - t.a)));
        if (dl > o.merge_distance_px) continue;
        // Along the common line: overlap, or a gap below D_gap.
        const double t0 = (t.a - s.a).dot(us), t1 = (t.b - s.a).dot(us), ls = len[i];
        const double gap = std::max({0.0, std::min(t0, t1) - ls, -std::max(t0, t1)});
        if (gap > o.merge_gap_px) continue;
        // The new segment: the two end points farthest apart.
        const std::array<Vector2d, 4> p{s.a, s.b, t.a, t.b};
        ImageSegment m{s.a, s.b};
        for (int a = 0; a < 4; ++a)
          for (int b = a + 1; b < 4; ++b)
            if ((p[b] - p[a]).norm() > length(m)) m = {p[a], p[b]};
        segs[i] = m;
        update(i);
        gone[j] = 1;
        merged = true;
        j = static_cast<size_t>(-1);   // the grown segment against all again (++j makes it 0)
      }
    }
  }
  std::vector<ImageSegment> out;
  out.reserve(segs.size());
  for (size_t i = 0; i < segs.size(); ++i)
    if (!gone[i] && len[i] >= o.min_length_px) out.push_back(segs[i]);
  std::stable_sort(out.begin(), out.end(), [](const ImageSegment& a, const ImageSegment& b) { return length(a) > length(b); });
  if (out.size() > static_cast<size_t>(o.max_segments)) out.resize(static_cast<size_t>(o.max_segments));
  return out;
}

std::vector<Quadrangle> group_quadrangles(const std::vector<ImageSegment>& segs, const QuadrangleOptions& o)
{
  const int n = static_cast<int>(segs.size());
  const double amin = std::min(o.alpha_min_deg, 180.0 - o.alpha_max_deg) * M_PI / 180.0;
  auto angle_ok = [&](int i, int j) { return line_angle(segs[i], segs[j]) > amin; };
  auto near = [&](int i, int j) {
    return geometry::corner_gap(segs[i].a, segs[i].b, segs[j].a, segs[j].b) < o.dn_max_px;
  };
  auto apart = [&](int i, int j) {
    return geometry::segments_distance(segs[i].a, segs[i].b, segs[j].a, segs[j].b) > o.do_min_px;
  };
  // Stage 1: valid pairs (corners).
  std::vector<std::pair<int, int>> pairs;
  std::vector<std::vector<char>> corner(static_cast<size_t>(n), std::vector<char>(static_cast<size_t>(n), 0));
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (angle_ok(i, j) && near(i, j)) {
        pairs.emplace_back(i, j);
        corner[i][j] = corner[j][i] = 1;
      }
  // Stage 2: pairs of pairs. Pair (i, j) and pair (k, l) in either order of k, l: the cycle
  // i-j-l-k with i-k and/or j-l near (non-restrictive), angles there fitting, and the opposite
  // sides i-l and j-k apart.
  const double min_in = o.min_internal_deg * M_PI / 180.0, max_in = o.max_internal_deg * M_PI / 180.0;
  std::vector<Quadrangle> quads;
  for (size_t p = 0; p < pairs.size(); ++p)
    for (size_t r = p + 1; r < pairs.size(); ++r)
      for (int swap = 0; swap < 2; ++swap) {
        const int i = pairs[p].first, j = pairs[p].second;
        const int k = swap ? pairs[r].second : pairs[r].first, l = swap ? pairs[r].first : pairs[r].second;
        if (k == i || k == j || l == i || l == j) continue;
        if (!(corner[i][k] || corner[j][l])) continue;
        if (corner[i][l] || corner[j][k]) continue;  // opposite sides that meet: no quadrangle
        if (!angle_ok(i, k) || !angle_ok(j, l) || !apart(i, l) || !apart(j, k)) continue;
        const Quadrangle q{meet(segs[i], segs[j]), meet(segs[j], segs[l]), meet(segs[l], segs[k]), meet(segs[k], segs[i])};
        if (!convex(q)) continue;
        const auto a = internal_angles(q);
        if (std::any_of(a.begin(), a.end(), [&](double x) { return x < min_in || x > max_in; })) continue;
        quads.push_back(q);
      }
  // Largest first; the same quadrangle again from other pieces of its sides (every corner within
  // DN_max of one of a kept one's) once. Nested ones stay: a whiteboard on a wall, a door's leaf
  // in its frame are objects of their own.
  std::sort(quads.begin(), quads.end(), [](const Quadrangle& a, const Quadrangle& b) { return area(a) > area(b); });
  std::vector<Quadrangle> kept;
  auto same = [&](const Quadrangle& a, const Quadrangle& b) {
    for (const auto& p : a)
      if (std::none_of(b.begin(), b.end(), [&](const Vector2d& c) { return (c - p).norm() < o.dn_max_px; })) return false;
    return true;
  };
  for (const auto& q : quads) {
    if (std::any_of(kept.begin(), kept.end(), [&](const Quadrangle& k) { return same(k, q); })) continue;
    kept.push_back(q);
    if (kept.size() >= static_cast<size_t>(o.max_quadrangles)) break;
  }
  return kept;
}

}  // namespace rgnav::vision
