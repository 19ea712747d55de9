#include "gateway_detector/narrow_passage.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::gateway_detector {

std::optional<ClosestPair> closest_pair(const sensors::LaserScan& scan, double am, double half)
{
  double best_l = std::numeric_limits<double>::infinity(), best_r = best_l;
  size_t il = 0, ir = 0;
  for (size_t i = 0; i < scan.size(); ++i) {
    if (!scan.hit(i)) continue;
    const double rel = geometry::normalize_angle(scan.bearing(i) - am);
    if (rel > 0 && rel < half && scan.ranges[i] < best_l) {
      best_l = scan.ranges[i];
      il = i;
    } else if (rel < 0 && rel > -half && scan.ranges[i] < best_r) {
      best_r = scan.ranges[i];
      ir = i;
    }
  }
  if (!std::isfinite(best_l) || !std::isfinite(best_r)) return std::nullopt;
  ClosestPair c;
  c.left = il;
  c.right = ir;
  const Vec2 pl = scan.point(il), pr = scan.point(ir);
  c.d_lr = (pl - pr).norm();
  c.aperture = geometry::normalize_angle(scan.bearing(il) - scan.bearing(ir));
  // P_is: where the segment pl-pr crosses the line of sight (the ray at alpha_m). The segment
  // joins a point left of the ray to one right of it, so the crossing exists.
  const Vec2 u(std::cos(am), std::sin(am)), nrm(-u.y(), u.x());
  const double sl = pl.dot(nrm), sr = pr.dot(nrm);
  const double t = sl / (sl - sr);
  const Vec2 pis = pl + t * (pr - pl);
  c.d_np = pis.norm();
  if (pis.dot(u) <= 0) return std::nullopt;  // the passage line passes behind the scanner
  return c;
}

std::optional<size_t> walk_to_gap(const sensors::LaserScan& scan, size_t from, size_t to, const NarrowPassageOptions& o)
{
  const double dmin = o.min_passage_width();
  const Vec2 opposite = scan.point(to);
  const int step = to > from ? 1 : -1;
  size_t cur = from;
  while (cur != to) {
    size_t next = cur + step;
    // Invalid readings say nothing: skip them.
    while (next != to && scan.invalid(next)) next += step;
    const Vec2 pc = scan.point(cur);
    if ((pc - opposite).norm() <= dmin) return std::nullopt;  // no room left for the robot
    const bool far = scan.no_return(next) || (scan.point(next) - pc).norm() >= dmin;
    if (far) {
      // A gap: is there free space of some depth behind the passage line, or just a step?
      const double behind = scan.no_return(next) ? scan.range_max : scan.ranges[next];
      if (behind - scan.ranges[cur] >= o.min_depth_behind) return cur;
      // A jump toward the scanner (something closer in between): not an opening here.
      return std::nullopt;
    }
    cur = next;
  }
  return std::nullopt;
}

double surface_extent(const sensors::LaserScan& scan, size_t i, double link)
{
  if (i >= scan.size() || !scan.hit(i)) return 0.0;
  auto walk = [&](int step) {
    size_t cur = i;
    for (;;) {
      const long next = static_cast<long>(cur) + step;
      if (next < 0 || next >= static_cast<long>(scan.size())) return cur;
      const auto n = static_cast<size_t>(next);
      if (!scan.hit(n) || (scan.point(n) - scan.point(cur)).norm() > link) return cur;
      cur = n;
    }
  };
  return (scan.point(walk(+1)) - scan.point(walk(-1))).norm();
}

std::vector<NarrowPassage> detect_narrow_passages(const sensors::LaserScan& scan, const NarrowPassageOptions& o)
{
  std::vector<NarrowPassage> out;
  const double dmin = o.min_passage_width();
  for (double am : o.viewing_directions) {
    const auto cp = closest_pair(scan, am, o.half_range);
    if (!cp) continue;
    if (cp->d_np >= o.max_distance) continue;  // D_NP < D_NP^max
    // Candidates: the closest points, and the gap edges found walking toward the other side.
    const auto gap_l = walk_to_gap(scan, cp->left, cp->right, o);
    const auto gap_r = walk_to_gap(scan, cp->right, cp->left, o);
    if (!gap_l && !gap_r) continue;  // no free space behind: invalid (fig. 4.11)
    std::vector<size_t> lefts{cp->left}, rights{cp->right};
    if (gap_l && *gap_l != cp->left) lefts.push_back(*gap_l);
    if (gap_r && *gap_r != cp->right) rights.push_back(*gap_r);

    std::optional<NarrowPassage> best;
    for (size_t l : lefts) {
      for (size_t r : rights) {
        NarrowPassage np;
        np.left = scan.point(l);
        np.right = scan.point(r);
        np.left_index = l;
        np.right_index = r;
        np.width = (np.left - np.right).norm();
        np.aperture = geometry::normalize_angle(scan.bearing(l) - scan.bearing(r));
        np.viewing_direction = am;
        // Distance along the line of sight to the passage line.
        const Vec2 u(std::cos(am), std::sin(am)), nrm(-u.y(), u.x());
        const double sl = np.left.dot(nrm), sr = np.right.dot(nrm);
        if (sl <= 0 || sr >= 0) continue;
        np.distance = (np.left + sl / (sl - sr) * (np.right - np.left)).norm();
        if (np.width <= dmin) continue;                                        // D_lr^min < D_lr
        if (np.width < o.min_width || np.width > o.max_width) continue;        // door width
        if (np.aperture < o.min_aperture || np.aperture > o.max_aperture) continue;
        if (np.distance >= o.max_distance) continue;
        if (o.min_jamb_extent > 0 && (surface_extent(scan, l, o.jamb_link_distance) < o.min_jamb_extent ||
                                      surface_extent(scan, r, o.jamb_link_distance) < o.min_jamb_extent))
          continue;
        if (!best || np.width < best->width) best = np;  // the pair of minimum distance
      }
    }
    if (!best) continue;
    bool dup = false;
    for (const auto& e : out)
      if ((e.left - best->left).norm() < 0.1 && (e.right - best->right).norm() < 0.1) dup = true;
    if (!dup) out.push_back(*best);
  }
  return out;
}

std::vector<NarrowPassage> detect_wall_gaps(const sensors::LaserScan& scan, const ScanFeatures& f, const NarrowPassageOptions& o)
{
  std::vector<NarrowPassage> out;
  const double dmin = o.min_passage_width();
  for (const auto& vl : f.virtual_lines) {
    if (vl.segments.size() < 2) continue;
    const Vec2 d = vl.line.direction(), foot = vl.line.foot();
    // Segment extents along the line, in order.
    std::vector<std::pair<double, double>> spans;
    for (int k : vl.segments) {
      const double ta = (f.segments[static_cast<size_t>(k)].a - foot).dot(d), tb = (f.segments[static_cast<size_t>(k)].b - foot).dot(d);
      spans.push_back({std::min(ta, tb), std::max(ta, tb)});
    }
    std::sort(spans.begin(), spans.end());
    for (size_t i = 0; i + 1 < spans.size(); ++i) {
      const double t0 = spans[i].second, t1 = spans[i + 1].first;
      const double width = t1 - t0;
      if (width <= dmin || width < o.min_width || width > o.max_width) continue;
      const Vec2 a = foot + t0 * d, b = foot + t1 * d;
      const Vec2 mid = 0.5 * (a + b);
      if (mid.norm() > o.wall_gap_max_distance) continue;
      // The beams through the gap must pass the wall line: an opening, not an occlusion.
      double ba = std::atan2(a.y(), a.x()), bb = std::atan2(b.y(), b.x());
      if (ba > bb) std::swap(ba, bb);
      int n = 0, through = 0;
      for (size_t j = 0; j < scan.size(); ++j) {
        const double bj = scan.bearing(j);
        if (bj <= ba || bj >= bb || scan.invalid(j)) continue;
        ++n;
        const double dl = ray_range(vl.line, bj);
        if (scan.no_return(j) || scan.ranges[j] > dl + o.min_depth_behind) ++through;
      }
      if (n < 2 || through < o.wall_gap_min_through * n) continue;
      NarrowPassage np;
      // Left = larger bearing, as for the forward detection.
      const bool a_left = std::atan2(a.y(), a.x()) > std::atan2(b.y(), b.x());
      np.left = a_left ? a : b;
      np.right = a_left ? b : a;
      np.left_index = scan.index_of(std::atan2(np.left.y(), np.left.x()));
      np.right_index = scan.index_of(std::atan2(np.right.y(), np.right.x()));
      np.width = width;
      np.distance = mid.norm();
      np.aperture = bb - ba;
      np.viewing_direction = std::atan2(mid.y(), mid.x());
      out.push_back(np);
    }
  }
  return out;
}

}  // namespace rgnav::gateway_detector
