#include "geometry/segment2.h"
#include "procs/rg_kernel/doorways.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "procs/rg_kernel/line_map.h"
#include "procs/rg_kernel/line_map_fidelity.h"
#include "procs/rg_kernel/region_builder.h"

namespace rgnav::rg_kernel {

using Eigen::Vector2d;

namespace {

// Distance of p from the infinite line through a and b.
double line_distance(const Vector2d& p, const Vector2d& a, const Vector2d& b)
{
  const Vector2d u = (b - a).normalized();
  const Vector2d d = p - a;
  return std::fabs(u.x() * d.y() - u.y() * d.x());
}

// Angle between the directions of two lines, in [0, pi/2].
double line_angle(const Vector2d& u, const Vector2d& v)
{
  const double c = std::fabs(u.normalized().dot(v.normalized()));
  return std::acos(std::min(1.0, c));
}

double segment_distance(const Vector2d& p, const rgmap::LineSegment& s) { return point_segment_distance(p, s.a, s.b); }

// The wall-end gaps of the line map (DoorwayOptions::wall_end_max_width), not repeating `found`.
void add_wall_end_gaps(const std::vector<rgmap::LineSegment>& segments, const DoorwayOptions& o, std::vector<Line>* found)
{
  // [m] hits nearer the end than this are the wall's own end face (a thick wall seen end-on).
  constexpr double kOwnEnd = 0.1;
  // [m] gaps whose middles are this near are one gap (the two faces of a thick wall).
  constexpr double kSameGap = 0.5;
  for (size_t i = 0; i < segments.size(); ++i) {
    const auto& w = segments[i];
    if (length(w) < o.wall_end_min_wall_length) continue;
    for (const auto& [end, other] : {std::pair{w.a, w.b}, std::pair{w.b, w.a}}) {
      const Vector2d u = (end - other).normalized();
      // A free end: no crossing wall (longer than a wall is thick) touches it.
      bool free = true;
      for (size_t j = 0; j < segments.size() && free; ++j)
        free = j == i || length(segments[j]) <= 2 * o.wall_end_free_radius ||
               line_angle(u, segments[j].b - segments[j].a) < o.wall_end_min_angle ||
               segment_distance(end, segments[j]) > o.wall_end_free_radius;
      if (!free) continue;
      // Not a jamb of an opening in another wall's line (that line through the end, across the wall,
      // the other wall apart from it).
      bool in_line = false;
      for (size_t j = 0; j < segments.size() && !in_line; ++j) {
        const auto& t = segments[j];
        in_line = j != i && length(t) >= o.min_wall_length && line_angle(u, t.b - t.a) >= o.wall_end_min_angle &&
                  segment_distance(end, t) > o.wall_end_free_radius &&   // not the wall's own end face
                  line_distance(end, t.a, t.b) <= o.wall_end_in_line_offset &&
                  std::min((t.a - end).norm(), (t.b - end).norm()) <= o.max_width;
      }
      if (in_line) continue;
      // The first line the wall's line runs into past its end: a crossing wall (through or a
      // corner of it) makes a gap; anything else in the way (furniture, a wall along it) does not.
      double nearest = std::numeric_limits<double>::max();
      bool crossing_wall = false;
      for (size_t j = 0; j < segments.size(); ++j) {
        if (j == i) continue;
        const auto& t = segments[j];
        const auto hit = ray_meets_line(end, u, t.a, t.b);
        if (!hit || hit->along_ray < kOwnEnd || hit->along_ray >= nearest) continue;
        const bool wall = length(t) >= o.wall_end_min_wall_length && line_angle(u, t.b - t.a) >= o.wall_end_min_angle;
        const double tolerance = wall ? o.wall_end_corner_tolerance / length(t) : 0.0;
        if (hit->along_line < -tolerance || hit->along_line > 1 + tolerance) continue;
        nearest = hit->along_ray;
        crossing_wall = wall;
      }
      if (!crossing_wall || nearest < o.min_width || nearest > o.wall_end_max_width) continue;
      const Line gap{end, end + nearest * u};
      const Vector2d mid = 0.5 * (gap.first + gap.second);
      const auto same = [&](const Line& l) { return (0.5 * (l.first + l.second) - mid).norm() < kSameGap; };
      if (std::none_of(found->begin(), found->end(), same)) found->push_back(gap);
    }
  }
}

}  // namespace

std::vector<Line> find_doorways(const std::vector<rgmap::LineSegment>& segments, const DoorwayOptions& o)
{
  std::vector<Line> out;
  if (!o.enabled) return out;
  std::vector<size_t> walls;
  for (size_t i = 0; i < segments.size(); ++i)
    if ((segments[i].b - segments[i].a).norm() >= o.min_wall_length) walls.push_back(i);
  for (size_t wi = 0; wi < walls.size(); ++wi) {
    const auto& s = segments[walls[wi]];
    for (size_t wj = wi + 1; wj < walls.size(); ++wj) {
      const auto& t = segments[walls[wj]];
      if (line_angle(s.b - s.a, t.b - t.a) > o.max_angle) continue;
      // The facing ends: the pair of end points, one of each, closest together.
      const Vector2d se[2] = {s.a, s.b}, te[2] = {t.a, t.b};
      int bi = 0, bj = 0;
      double best = std::numeric_limits<double>::max();
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          if (const double d = (se[i] - te[j]).norm(); d < best) best = d, bi = i, bj = j;
      if (best < o.min_width || best > o.max_width) continue;
      const Vector2d p = se[bi], q = te[bj];
      // One straight wall with a gap: the gap lies along both pieces, each end on the other's line,
      // and the pieces lie on either side of the gap (not overlapping side by side).
      if (line_angle(q - p, s.b - s.a) > o.max_angle) continue;
      if (line_distance(q, s.a, s.b) > o.max_offset || line_distance(p, t.a, t.b) > o.max_offset) continue;
      const Vector2d u = (q - p).normalized();
      if (u.dot(se[1 - bi] - p) > 0 || u.dot(te[1 - bj] - q) < 0) continue;
      out.push_back({p, q});
    }
  }
  if (o.wall_end_max_width > 0) add_wall_end_gaps(segments, o, &out);
  return out;
}

std::optional<Line> doorway_stepped_through(const std::vector<rgmap::LineSegment>& segments, const Vector2d& from,
                                            const Vector2d& to, const DoorwayOptions& o)
{
  if (!o.enabled || (to - from).norm() > o.max_width) return std::nullopt;
  // Only wall pieces near the step can frame a doorway it goes through.
  // (A wall-end gap's wall lies beside it: as far as the gap is wide plus the wall's length.)
  const double frame = std::max(o.max_width, o.wall_end_max_width + o.wall_end_min_wall_length);
  const double reach = frame + 0.5 * (to - from).norm() + 0.5;
  const Vector2d mid = 0.5 * (from + to);
  std::vector<rgmap::LineSegment> near;
  for (const auto& seg : segments)
    if (segment_distance(mid, seg) <= reach) near.push_back(seg);
  for (const auto& [p, q] : find_doorways(near, o))
    if (geometry::segments_cross(from, to, p, q)) return Line{p, q};
  return std::nullopt;
}

std::vector<Line> doorways_not_crossed(const std::vector<Line>& doorways, const std::vector<Vector2d>& path)
{
  std::vector<Line> out;
  for (const auto& [a, b] : doorways) {
    bool crossed = false;
    for (size_t k = 0; k + 1 < path.size() && !crossed; ++k) crossed = geometry::segments_cross(path[k], path[k + 1], a, b);
    if (!crossed) out.push_back({a, b});
  }
  return out;
}

}  // namespace rgnav::rg_kernel
