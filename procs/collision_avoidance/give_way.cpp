#include "collision_avoidance/give_way.h"

#include <cmath>

#include "collision_avoidance/chain_planner.h"

namespace rgnav::collision_avoidance {

std::optional<GiveWay> choose_give_way(const LocalMap& map, const Eigen::Vector2d& from, double away, double clearance,
                                       double step, const GiveWayOptions& o)
{
  std::optional<GiveWay> best;
  double best_score = 0.0;
  const int n = std::max(1, o.headings);
  for (int k = 0; k < n; ++k) {
    // Straight back first, then alternating outward, so ties keep the most direct heading.
    const int i = (k + 1) / 2 * (k % 2 ? 1 : -1);
    const double dev = n > 1 ? o.spread * i / ((n - 1) / 2.0) : 0.0;
    if (std::fabs(dev) > o.spread + 1e-9) continue;
    const double heading = geometry::normalize_angle(away + dev);
    const trajectory::Chain line({trajectory::Segment::line(Pose2(from, heading), o.length)});
    double free = o.length;
    if (const auto hit = first_collision(line, map, clearance, step)) free = *hit - step;
    if (free < o.min_length) continue;
    const double score = free * (0.5 + 0.5 * std::cos(dev));  // sideways counts half
    if (score > best_score + 1e-9) {
      best_score = score;
      best = GiveWay{heading, free};
    }
  }
  return best;
}

}  // namespace rgnav::collision_avoidance
