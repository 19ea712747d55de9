#include "planner/route.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::planner {

using geometry::Pose2;

std::vector<int64_t> Route::gateways() const
{
  std::vector<int64_t> out;
  for (const auto& l : legs)
    if (l.exit_gateway) out.push_back(l.exit_gateway);
  return out;
}

double project_onto_leg(const RouteLeg& leg, const Eigen::Vector2d& p, double from, double* distance)
{
  // The nearest point of the path no earlier than a little before `from` and no farther ahead
  // than a window (a path that comes back near itself must not make progress jump).
  constexpr double kBack = 0.5, kWindow = 6.0;
  double best_s = from, best_d = std::numeric_limits<double>::infinity(), s0 = 0;
  for (size_t i = 0; i + 1 < leg.points.size(); ++i) {
    const Eigen::Vector2d a = leg.points[i], d = leg.points[i + 1] - a;
    const double len = d.norm();
    if (s0 + len >= from - kBack && s0 <= from + kWindow) {
      const double t = len > 0 ? std::clamp((p - a).dot(d) / (len * len), 0.0, 1.0) : 0.0;
      const double dist = (a + t * d - p).norm();
      if (dist < best_d) {
        best_d = dist;
        best_s = s0 + t * len;
      }
    }
    s0 += len;
  }
  if (leg.points.size() == 1) best_d = (leg.points[0] - p).norm();
  if (distance) *distance = best_d;
  return std::max(from, best_s);
}

Eigen::Vector2d point_along(const RouteLeg& leg, double arc)
{
  if (leg.points.empty()) return Eigen::Vector2d::Zero();
  double s0 = 0;
  for (size_t i = 0; i + 1 < leg.points.size(); ++i) {
    const Eigen::Vector2d d = leg.points[i + 1] - leg.points[i];
    const double len = d.norm();
    if (s0 + len >= arc && len > 0) return leg.points[i] + d * (std::max(0.0, arc - s0) / len);
    s0 += len;
  }
  return leg.points.back();
}

double Route::leg_start(size_t leg) const
{
  double s = 0;
  for (size_t k = 0; k < leg && k < legs.size(); ++k) s += legs[k].length;
  return s;
}

Pose2 Route::frame_of(size_t from, size_t to) const
{
  Pose2 f;
  for (size_t k = from; k < to && k < legs.size(); ++k) f = f * legs[k].this_from_next;
  return f;
}

std::vector<RouteTarget> cut_targets(const Route& route, double spacing_min, double spacing_max)
{
  constexpr double kBendTolerance = 0.1;   // [m] a skipped bend may lie this far off the line past it
  constexpr double kMinStep = 0.25;        // [m] targets are never closer than this
  std::vector<RouteTarget> out;
  if (route.empty() || route.legs.front().points.empty()) return out;
  // `last`: the last target (or the start), in the frame of the leg being walked.
  Eigen::Vector2d last = route.legs.front().points.front();
  double last_arc = 0, arc = 0;
  for (size_t k = 0; k < route.legs.size(); ++k) {
    const auto& pts = route.legs[k].points;
    if (k > 0) last = route.legs[k - 1].this_from_next.inverse() * last;
    for (size_t i = 1; i < pts.size(); ++i) {
      arc += (pts[i] - pts[i - 1]).norm();
      const bool end = k + 1 == route.legs.size() && i + 1 == pts.size();
      const double d = arc - last_arc;
      // A bend nearer than spacing_min is skipped only when the path hardly bends there: the
      // straight line past it would cut a corner (a door's jamb) that the path goes round.
      if (d < spacing_min && !end) {
        const bool crossing = i + 1 == pts.size();   // the door itself: the line through it matters
        const Eigen::Vector2d next = i + 1 < pts.size() ? pts[i + 1] : pts[i];
        const Eigen::Vector2d chord = next - last;
        const double off = chord.norm() > 1e-9 ? std::abs(chord.x() * (pts[i] - last).y() - chord.y() * (pts[i] - last).x()) / chord.norm()
                                               : 0.0;
        if (!(crossing && d >= kMinStep) && !(off > kBendTolerance && d >= kMinStep)) continue;
      }
      if (d <= 1e-9) continue;
      const int pieces = std::max(1, static_cast<int>(std::ceil(d / spacing_max - 1e-9)));
      for (int j = 1; j <= pieces; ++j) {
        const double f = static_cast<double>(j) / pieces;
        const Eigen::Vector2d p = last + (pts[i] - last) * f;
        const Eigen::Vector2d dir = pts[i] - last;
        out.push_back({k, last_arc + d * f, Pose2(p, std::atan2(dir.y(), dir.x()))});
      }
      last = pts[i];
      last_arc = arc;
    }
  }
  if (out.empty()) {
    // Start and goal are one point: the goal alone.
    const auto& leg = route.legs.back();
    out.push_back({route.legs.size() - 1, 0.0, Pose2(leg.points.back(), route.goal_heading)});
  }
  // The goal closer than spacing_min to the target before it: that one goes.
  if (out.size() >= 2 && out.back().arc - out[out.size() - 2].arc < spacing_min) out.erase(out.end() - 2);
  if (route.has_goal_heading) out.back().pose = Pose2(out.back().pose.translation(), route.goal_heading);
  return out;
}

}  // namespace rgnav::planner
