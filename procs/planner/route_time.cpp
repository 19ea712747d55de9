#include "planner/route_time.h"

#include <cmath>
#include <vector>

#include "trajectory/construct.h"

namespace rgnav::planner {

using geometry::Pose2;

double predicted_time(const Route& route, const trajectory::Limits& limits)
{
  // The whole path in the first leg's frame.
  std::vector<Eigen::Vector2d> pts;
  for (size_t k = 0; k < route.legs.size(); ++k) {
    const Pose2 first_from_leg = route.frame_of(0, k);
    for (const auto& p : route.legs[k].points) {
      const Eigen::Vector2d q = first_from_leg * p;
      if (pts.empty() || (q - pts.back()).norm() > 1e-3) pts.push_back(q);
    }
  }
  if (pts.size() < 2) return 0.0;
  auto heading = [&](size_t i) {
    const Eigen::Vector2d d = pts[i + 1] - pts[i];
    return std::atan2(d.y(), d.x());
  };
  // The sharpest bend driven at speed: lateral acceleration and rotational velocity at v_max.
  const double kappa = std::min(limits.a_lat_max / (limits.v_max * limits.v_max), limits.omega_max / limits.v_max);
  trajectory::Chain chain;
  Pose2 at(pts[0], heading(0));
  for (size_t i = 1; i < pts.size(); ++i) {
    const bool last = i + 1 == pts.size();
    // Drive to the middle of the next piece (or the end), turning at pts[i] on the way.
    const Eigen::Vector2d to = last ? pts[i] : Eigen::Vector2d(0.5 * (pts[i] + pts[i + 1]));
    const double h_in = heading(i - 1);
    if (std::abs(geometry::normalize_angle(at.theta() - h_in)) > 1e-6) {
      chain.append_at_end(trajectory::Segment::turn(at, geometry::normalize_angle(h_in - at.theta())));
      at = Pose2(at.translation(), h_in);
    }
    if (last) {
      chain.append_at_end(trajectory::Segment::line(at, (to - at.translation()).norm()));
      break;
    }
    const Pose2 end(to, heading(i));
    if (auto corner = trajectory::line_arc_line(at, end, kappa)) {
      for (const auto& s : corner->segments()) chain.append_at_end(s);
    } else {
      // Too sharp for a driven arc: up to the bend, turn in place, on.
      chain.append_at_end(trajectory::Segment::line(at, (pts[i] - at.translation()).norm()));
      chain.append_at_end(trajectory::Segment::turn(Pose2(pts[i], h_in), geometry::normalize_angle(heading(i) - h_in)));
      chain.append_at_end(trajectory::Segment::line(Pose2(pts[i], heading(i)), (to - pts[i]).norm()));
    }
    at = end;
  }
  if (chain.empty()) return route.length / limits.v_max;
  return trajectory::VelocityProfile::compute(chain, limits, 0.0, 0.0).total_time();
}

}  // namespace rgnav::planner
