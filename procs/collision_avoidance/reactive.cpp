#include "collision_avoidance/reactive.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::collision_avoidance {

double freespace_orientation(const std::vector<PolarReading>& readings, const ReactiveOptions& o)
{
  double sx = 0.0, sy = 0.0;
  for (const auto& r : readings) {
    if (std::fabs(r.bearing) > 1.2 * M_PI_2) continue;  // f_th < 0 behind: no vote
    const double fth = std::cos(r.bearing / 1.2);
    const double fd = 1.0 / (1.0 + std::exp(-(r.range - o.dto_max) / o.dto_min));
    sx += std::cos(r.bearing) * fth * fd;
    sy += std::sin(r.bearing) * fth * fd;
  }
  if (sx == 0.0 && sy == 0.0) return 0.0;
  return std::atan2(sy, sx);
}

double corridor_distance(const std::vector<Eigen::Vector2d>& pts, double direction, double half_width)
{
  const double c = std::cos(direction), s = std::sin(direction);
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : pts) {
    const double along = c * p.x() + s * p.y(), across = -s * p.x() + c * p.y();
    if (along > 0 && std::fabs(across) <= half_width) best = std::min(best, along);
  }
  return best;
}

ReactiveDecision decide(const std::vector<PolarReading>& readings, double target_bearing, bool standing,
                        const ReactiveOptions& o)
{
  std::vector<Eigen::Vector2d> pts;
  pts.reserve(readings.size());
  for (const auto& r : readings) pts.emplace_back(r.range * std::cos(r.bearing), r.range * std::sin(r.bearing));
  const double alpha_free = freespace_orientation(readings, o);
  // Prefer the target's direction when its corridor is open beyond dto_max; else free space.
  const double d_target = corridor_distance(pts, target_bearing, o.corridor_half_width);
  const double d_free = corridor_distance(pts, alpha_free, o.corridor_half_width);
  const bool target_open = d_target > o.dto_min + 0.3 && std::fabs(target_bearing) < M_PI_2;
  const double heading = target_open ? target_bearing : alpha_free;
  const double ahead = corridor_distance(pts, 0.0, o.corridor_half_width);
  ReactiveDecision d;
  d.heading = heading;
  d.corridor_distance = ahead;
  const double d_heading = target_open ? d_target : d_free;
  if (std::fabs(heading) > 0.5 || ahead < o.dto_min) {
    // Not facing the way out, or blocked ahead: stop, and once stopped turn on the spot.
    if (standing && d_heading > o.dto_min) {
      d.action = ReactiveDecision::Action::kTurn;
      d.heading = std::clamp(heading, -o.max_turn, o.max_turn);
    } else if (standing) {
      // Nowhere to go in that direction either: turn toward free space anyway (dead end).
      d.action = ReactiveDecision::Action::kTurn;
      d.heading = std::clamp(alpha_free == 0.0 ? M_PI_2 : alpha_free, -o.max_turn, o.max_turn);
    } else {
      d.action = ReactiveDecision::Action::kStop;
    }
    return d;
  }
  // Slow down with the distance in the corridor (dto_min -> 0, dto_max -> full speed).
  const double frac = std::clamp((std::min(ahead, d_heading) - o.dto_min) / (o.dto_max - o.dto_min), 0.0, 1.0);
  d.action = frac > 0 ? ReactiveDecision::Action::kDrive : ReactiveDecision::Action::kStop;
  d.speed = o.v_max * frac;
  return d;
}

}  // namespace rgnav::collision_avoidance
