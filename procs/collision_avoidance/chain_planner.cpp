#include "collision_avoidance/chain_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "trajectory/construct.h"

namespace rgnav::collision_avoidance {

using trajectory::Chain;
using trajectory::Kind;
using trajectory::Segment;

namespace {

// The clearance a chain needs at arc length s when it starts at s_from with clearance c0:
// the full `clearance`, except that a robot already closer than that to something (a box
// seen late, a person who stepped close) may leave: moving away at a slope of kLeaveSlope
// metres of clearance per metre driven is allowed, getting closer is not.
constexpr double kLeaveSlope = 0.5;
// A robot only a little short of the clearance from static things (a narrow hallway's wall a
// few centimetres nearer than the margin after a turn on the spot bent the odometry) has to
// make that up within kMakeUpWithin of driving, not at kLeaveSlope: no smooth chain along a
// hallway gains 0.5 m of clearance per metre, and the robot stood turning on the spot for good.
constexpr double kNearlyClear = 0.05;   // [m] short of the clearance by at most this
constexpr double kMakeUpWithin = 1.0;   // [m]

double required(double clearance, double c0, double s_from, double s)
{
  return std::min(clearance, c0 - 0.01 + kLeaveSlope * std::max(0.0, s - s_from));
}

// The same for first_collision (everything the map holds at the plain clearance), with the
// gentler slope when nearly clear; the extra margin from what may move keeps the steep one.
double required_static(double clearance, double c0, double s_from, double s)
{
  const double short_by = clearance - c0;
  const double slope = short_by <= kNearlyClear ? std::min(kLeaveSlope, (short_by + 0.01) / kMakeUpWithin) : kLeaveSlope;
  return std::min(clearance, c0 - 0.01 + slope * std::max(0.0, s - s_from));
}

}  // namespace

double required_clearance(double clearance, double c0, double s) { return required_static(clearance, c0, 0.0, s); }

std::optional<double> first_collision(const Chain& chain, const LocalMap& map, double clearance, double step,
                                      double s_from)
{
  const double c0 = map.clearance(chain.pose_at(s_from).translation(), clearance);
  for (size_t i = 0; i < chain.size(); ++i) {
    const Segment& seg = chain[i];
    const double a = chain.start_s(i);
    if (a + seg.length() < s_from) continue;
    if (seg.kind() == Kind::kTurn) {
      if (map.clearance(seg.start().translation(), clearance) < required_static(clearance, c0, s_from, a)) return a;
      continue;
    }
    const int n = std::max(1, static_cast<int>(std::ceil(seg.length() / step)));
    for (int j = 0; j <= n; ++j) {
      const double ls = seg.length() * j / n;
      if (a + ls < s_from) continue;
      if (map.clearance(seg.pose_at(ls).translation(), clearance) < required_static(clearance, c0, s_from, a + ls))
        return a + ls;
    }
  }
  return std::nullopt;
}

std::optional<double> first_collision_near(const Chain& chain, const LocalMap& map, const PlannerOptions& o,
                                           double s_from)
{
  const double base = o.robot_radius + o.safety_margin;
  if (auto s = first_collision(chain, map, base, o.check_step, s_from)) return s;
  // The near part keeps the extra margin from whatever may be moving (people step in from
  // the side faster than the map ages); static obstacles (door frames) only need the plain
  // margin, so doors stay passable. The check simply stops at s_from + near_length.
  if (map.moving_size() == 0) return std::nullopt;
  const double s_to = s_from + o.near_length, near = base + o.near_margin;
  const double c0 = map.clearance_moving(chain.pose_at(s_from).translation(), near);
  for (size_t i = 0; i < chain.size(); ++i) {
    const Segment& seg = chain[i];
    const double a = chain.start_s(i);
    if (a > s_to) break;
    if (a + seg.length() < s_from) continue;
    const int n = std::max(1, static_cast<int>(std::ceil(seg.length() / o.check_step)));
    for (int j = 0; j <= n; ++j) {
      const double s = a + seg.length() * j / n;
      if (s < s_from || s > s_to) continue;
      if (map.clearance_moving(seg.pose_at(s - a).translation(), near) < required(near, c0, s_from, s)) return s;
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
  return finish(std::move(total), v_start, map, lim);
}

std::optional<PlannedChain> ChainPlanner::plan_along(const Pose2& start, double v_start,
                                                     const std::vector<Eigen::Vector2d>& corners,
                                                     std::optional<double> final_heading, const LocalMap& map,
                                                     double v_max) const
{
  if (corners.empty()) return std::nullopt;
  trajectory::Limits lim = options_.limits;
  lim.v_max = std::min(lim.v_max, v_max);
  const bool standing = std::fabs(v_start) < 0.05;
  auto leg_heading = [&](size_t k) {
    const Eigen::Vector2d a = k == 0 ? start.translation() : corners[k - 1];
    const Eigen::Vector2d d = corners[k] - a;
    return std::atan2(d.y(), d.x());
  };
  std::vector<Chain> options;
  // (a) Smooth: clothoids through the corners, each passed along the bisector of its legs.
  {
    Chain c;
    Pose2 from = start;
    const double bearing = geometry::normalize_angle(leg_heading(0) - start.theta());
    bool ok = true;
    if (std::fabs(bearing) > 0.5) {
      if (!standing) ok = false;
      else {
        c.push_back(Segment::turn(start, bearing));
        from = c.end();
      }
    }
    for (size_t k = 0; ok && k < corners.size(); ++k) {
      double heading = leg_heading(k);
      if (k + 1 < corners.size())
        heading += 0.5 * geometry::normalize_angle(leg_heading(k + 1) - leg_heading(k));
      else if (final_heading)
        heading = *final_heading;
      const auto seg = trajectory::clothoid_g1(from, Pose2(corners[k], heading));
      if (!seg) ok = false;
      else {
        c.push_back(*seg);
        from = c.end();
      }
    }
    if (ok) options.push_back(std::move(c));
  }
  // (b) Polyline: turn on the spot at every corner, straight legs between (a synchro drive
  // can always do this, at the cost of stopping at the corners).
  if (standing) {
    Chain c;
    Pose2 from = start;
    for (size_t k = 0; k < corners.size(); ++k) {
      const double dth = geometry::normalize_angle(leg_heading(k) - from.theta());
      if (std::fabs(dth) > 1e-3) {
        c.push_back(Segment::turn(from, dth));
        from = c.end();
      }
      const double len = (corners[k] - from.translation()).norm();
      if (len > 1e-3) {
        c.push_back(Segment::line(from, len));
        from = c.end();
      }
    }
    if (final_heading) {
      const double dth = geometry::normalize_angle(*final_heading - from.theta());
      if (std::fabs(dth) > 1e-3) c.push_back(Segment::turn(from, dth));
    }
    if (!c.empty()) options.push_back(std::move(c));
  }
  std::optional<Chain> best;
  double best_cost = std::numeric_limits<double>::infinity();
  for (Chain& c : options) {
    if (!acceptable(c, std::numeric_limits<double>::infinity())) continue;
    if (first_collision_near(c, map, options_, 0.0)) continue;
    const double t = trajectory::VelocityProfile::compute(c, lim, v_start, 0.0, 0.05).total_time();
    if (t < best_cost) {
      best_cost = t;
      best = std::move(c);
    }
  }
  if (!best) return std::nullopt;
  return finish(std::move(*best), v_start, map, lim);
}

std::optional<PlannedChain> ChainPlanner::finish(Chain total, double v_start, const LocalMap& map,
                                                 const trajectory::Limits& lim) const
{
  const double clearance = options_.robot_radius + options_.safety_margin;
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
