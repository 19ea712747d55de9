#include "gateway_detector/vlm.h"

#include <algorithm>
#include <cmath>

namespace rgnav::gateway_detector {

bool make_vlm(const Line& left, const Line& right, const Line& front, const Line& hidden, Vlm* out)
{
  Vlm v;
  v.left = left;
  v.right = right;
  v.front = front;
  v.hidden = hidden;
  if (!intersect(left, hidden, &v.points[0]) || !intersect(left, front, &v.points[1]) ||
      !intersect(right, front, &v.points[2]) || !intersect(right, hidden, &v.points[3]))
    return false;
  const Vec2 entry_mid = 0.5 * (v.points[0] + v.points[3]);
  const Vec2 front_mid = 0.5 * (v.points[1] + v.points[2]);
  const Vec2 along = front_mid - entry_mid;
  if (along.norm() < 1e-6) return false;
  v.axis = along.normalized();
  *out = v;
  return true;
}

namespace {

bool same(const Vlm& a, const Vlm& b, double tol)
{
  for (int i = 0; i < 4; ++i)
    if ((a.points[i] - b.points[i]).norm() > tol) return false;
  return true;
}

// The line through p parallel to `like`.
Line parallel_through(const Line& like, const Vec2& p) { return Line{like.theta, p.dot(like.normal())}; }

}  // namespace

std::vector<Vlm> group_vlms(const ScanFeatures& f, const VlmOptions& o)
{
  const auto& vls = f.virtual_lines;
  const double dhw = o.hallway_width;
  struct Candidate
  {
    Vlm vlm;
    double support;
  };
  std::vector<Candidate> out;

  for (size_t i = 0; i < vls.size(); ++i) {
    for (size_t j = 0; j < vls.size(); ++j) {
      if (i == j || vls[i].support < o.min_side_support || vls[j].support < o.min_side_support) continue;
      const Line& a = vls[i].line;
      const Line& b = vls[j].line;
      if (angle_between(a, b) > o.parallel_angle) continue;
      // The robot lies between them: normals (pointing away from the origin) are opposite.
      if (a.normal().dot(b.normal()) > -0.5) continue;
      const double width = a.rho + b.rho;
      if (width < o.width_min_factor * dhw || width > o.width_max_factor * dhw) continue;
      // Hallway direction: along the lines, pointing forward (+x of the laser).
      Vec2 axis = a.direction();
      if (axis.x() < 0) axis = -axis;
      const Vec2 leftward(-axis.y(), axis.x());
      // i is the left line: its normal points to the left of the axis (j takes the other role
      // in the mirrored iteration).
      if (a.normal().dot(leftward) <= 0) continue;
      const Line& left = a;
      const Line& right = b;

      for (size_t k = 0; k < vls.size(); ++k) {
        if (k == i || k == j || vls[k].support < o.min_front_support) continue;
        const Line& front = vls[k].line;
        if (std::fabs(angle_between(front, left) - M_PI / 2) > o.right_angle_tolerance) continue;
        Vec2 pl, pr;
        if (!intersect(left, front, &pl) || !intersect(right, front, &pr)) continue;
        const double front_along = 0.5 * (pl + pr).dot(axis);
        if (front_along <= 0 || (0.5 * (pl + pr)).norm() > o.max_front_distance) continue;

        std::vector<std::pair<Line, bool>> hidden;
        for (const auto& s : f.singularities) {
          if (std::fabs(left.signed_distance(s.point)) > o.singularity_line_distance &&
              std::fabs(right.signed_distance(s.point)) > o.singularity_line_distance)
            continue;
          const double depth = front_along - s.point.dot(axis);
          if (depth < o.min_depth_factor * dhw || depth > o.max_depth_factor * dhw) continue;
          hidden.push_back({parallel_through(front, s.point), true});
        }
        // The hallway-width prior: one d_hw before the front line.
        hidden.push_back({parallel_through(front, 0.5 * (pl + pr) - dhw * axis), false});

        for (const auto& [h, from_singularity] : hidden) {
          Vlm v;
          if (!make_vlm(left, right, front, h, &v)) continue;
          v.hidden_from_singularity = from_singularity;
          const double support = vls[i].support + vls[j].support + vls[k].support + (from_singularity ? 1.0 : 0.0);
          bool dup = false;
          for (auto& c : out) {
            if (same(c.vlm, v, o.duplicate_distance)) {
              dup = true;
              if (support > c.support) c = {v, support};
              break;
            }
          }
          if (!dup) out.push_back({v, support});
        }
      }
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) { return a.support > b.support; });
  if (static_cast<int>(out.size()) > o.max_hypotheses) out.resize(static_cast<size_t>(o.max_hypotheses));
  std::vector<Vlm> result;
  for (auto& c : out) result.push_back(c.vlm);
  return result;
}

}  // namespace rgnav::gateway_detector
