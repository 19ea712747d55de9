#include "collision_avoidance/chain_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "trajectory/construct.h"

namespace rgnav::collision_avoidance {

using trajectory::Chain;
using trajectory::Kind;
using trajectory::Segment;

std::optional<double> first_collision(const Chain& chain, const LocalMap& map, double clearance, double step,
                                      double s_from)
{
  for (size_t i = 0; i < chain.size(); ++i) {
    const Segment& seg = chain[i];
    const double a = chain.start_s(i);
    if (a + seg.length() < s_from) continue;
    if (seg.kind() == Kind::kTurn) {
      if (map.clearance(seg.start().translation(), clearance) < clearance) return a;
      continue;
    }
    const int n = std::max(1, static_cast<int>(std::ceil(seg.length() / step)));
    for (int j = 0; j <= n; ++j) {
      const double ls = seg.length() * j / n;
      if (a + ls < s_from) continue;
      if (map.clearance(seg.pose_at(ls).translation(), clearance) < clearance) return a + ls;
    }
  }
  return std::nullopt;
}

std::optional<double> first_collision_near(const Chain& chain, const LocalMap& map, const PlannerOptions& o,
                                           double s_from)
{
  const double base = o.robot_radius + o.safety_margin;
  if (auto s = first_collision(chain, map, base, o.check_step, s_from)) return s;
  // The near part with the extra margin: a shortened copy of the chain is not needed, the
  // check simply stops at s_from + near_length.
  const double s_to = s_from + o.near_length, near = base + o.near_margin;
  for (size_t i = 0; i < chain.size(); ++i) {
    const Segment& seg = chain[i];
    const double a = chain.start_s(i);
    if (a > s_to) break;
    if (a + seg.length() < s_from) continue;
    const int n = std::max(1, static_cast<int>(std::ceil(seg.length() / o.check_step)));
    for (int j = 0; j <= n; ++j) {
      const double s = a + seg.length() * j / n;
      if (s < s_from || s > s_to) continue;
      if (map.clearance(seg.pose_at(s - a).translation(), near) < near) return s;
    }
  }
  return std::nullopt;
}

bool ChainPlanner::acceptable(const Chain& c, double direct) const
{
  if (c.empty()) return false;
  if (c.length() > options_.max_length_ratio * std::max(direct, 0.3)) return false;
  for (size_t i = 0; i < c.size(); ++i) {
    const Segment& s = c[i];
    if (s.kind() == Kind::kTurn) continue;
    if (std::max(std::fabs(s.curvature_at(0.0)), std::fabs(s.curvature_at(s.length()))) > options_.kappa_max)
      return false;
    if (s.kind() == Kind::kConic &&
        std::fabs(s.curvature_at(0.5 * s.length())) > options_.kappa_max)
      return false;
  }
  return true;
}

std::vector<Chain> ChainPlanner::candidates(const Pose2& from, const Pose2& to, bool standing) const
{
  std::vector<Chain> out;
  const Eigen::Vector2d d = to.translation() - from.translation();
  const double dist = d.norm();
  if (dist < 1e-3) {
    // Only the heading differs: turn on the spot.
    const double dth = geometry::normalize_angle(to.theta() - from.theta());
    if (std::fabs(dth) > 1e-3) out.push_back(Chain({Segment::turn(from, dth)}));
    return out;
  }
  const double bearing = geometry::normalize_angle(std::atan2(d.y(), d.x()) - from.theta());
  Pose2 start = from;
  Chain prefix;
  if (std::fabs(bearing) > options_.turn_first_angle) {
    if (!standing) return out;  // no turning in place at speed
    prefix.push_back(Segment::turn(from, bearing));
    start = prefix.end();
  }
  auto add = [&](std::optional<Chain> c) {
    if (!c) return;
    Chain full = prefix;
    for (const auto& s : c->segments()) full.push_back(s);
    out.push_back(std::move(full));
  };
  if (auto s = trajectory::clothoid_g1(start, to)) add(Chain({*s}));
  add(trajectory::line_turn_line_g2(start, to, options_.kappa_max));
  for (double k : {options_.kappa_max, 0.5 * options_.kappa_max}) add(trajectory::dubins(start, to, k));
  // Detours: through a via-pose beside the straight line, heading parallel to it.
  const double line_heading = std::atan2(d.y(), d.x());
  const Eigen::Vector2d fwd = d / dist, left(-fwd.y(), fwd.x());
  for (double off : options_.detour_offsets)
    for (double sgn : {1.0, -1.0})
      for (double frac : {0.5, 0.35, 0.65})
        for (double dh : {0.0, 0.4, -0.4}) {
          const Pose2 via(start.translation() + frac * d + sgn * off * left, line_heading + dh);
          const auto a = trajectory::clothoid_g1(start, via);
          const auto b = trajectory::clothoid_g1(via, to);
          if (a && b) add(Chain({*a, *b}));
        }
  return out;
}

std::optional<PlannedChain> ChainPlanner::plan(const Pose2& start, double v_start, const std::vector<Pose2>& goals,
                                               const LocalMap& map, double v_max) const
{
  const double clearance = options_.robot_radius + options_.safety_margin;
  trajectory::Limits lim = options_.limits;
  lim.v_max = std::min(lim.v_max, v_max);
  Chain total;
  Pose2 from = start;
  double v_from = v_start;
  for (size_t g = 0; g < goals.size(); ++g) {
    const double direct = (goals[g].translation() - from.translation()).norm();
    std::optional<Chain> best;
    double best_cost = std::numeric_limits<double>::infinity();
    for (Chain& c : candidates(from, goals[g], std::fabs(v_from) < 0.05)) {
      if (!acceptable(c, direct)) continue;
      if (g == 0 ? first_collision_near(c, map, options_, 0.0).has_value()
                 : first_collision(c, map, clearance, options_.check_step).has_value())
        continue;
      // Cost: predicted time of this leg from the current speed, ending at rest.
      const double t = trajectory::VelocityProfile::compute(c, lim, v_from, 0.0, 0.05).total_time();
      if (t < best_cost) {
        best_cost = t;
        best = std::move(c);
      }
    }
    if (!best) break;
    for (const auto& s : best->segments()) total.push_back(s);
    from = total.end();
    v_from = 0.3;  // legs after the first are entered moving (only matters for turn-first)
    if (g == 0 && goals.size() > 1) v_from = v_max;
  }
  if (total.empty()) return std::nullopt;
  // Speed limits from the clearance of each segment.
  {
    std::vector<Segment> limited;
    for (Segment seg : total.segments()) {
      double c = std::numeric_limits<double>::infinity();
      const int n = std::max(1, static_cast<int>(std::ceil(seg.length() / 0.1)));
      for (int j = 0; j <= n; ++j)
        c = std::min(c, map.clearance(seg.pose_at(seg.length() * j / n).translation(), clearance + options_.slow_band));
      const double frac = std::clamp((c - clearance) / options_.slow_band, 0.0, 1.0);
      const double v = std::min(lim.v_max, options_.slow_speed + (lim.v_max - options_.slow_speed) * frac);
      seg.set_v_max(std::min(seg.v_max(), v));
      limited.push_back(seg);
    }
    total = Chain(limited);
  }
  PlannedChain out;
  out.predicted_time = trajectory::VelocityProfile::compute(total, lim, v_start, 0.0).total_time();
  out.min_clearance = std::numeric_limits<double>::infinity();
  for (double s = 0; s <= total.length(); s += 0.1)
    out.min_clearance = std::min(out.min_clearance, map.clearance(total.pose_at(s).translation(), 2.0));
  out.chain = std::move(total);
  return out;
}

}  // namespace rgnav::collision_avoidance
