#include "collision_avoidance/own_track.h"

#include <algorithm>
#include <cmath>

namespace rgnav::collision_avoidance {

namespace {

// Points of a track farther than this from the robot: it is not on its track.
constexpr double kOnTrack = 0.3;    // [m]
// A straight leg of the way back may cut the track's corners by this much.
constexpr double kCutCorner = 0.03; // [m]
// Within this of the start the way back may be as tight as the start is now: the robot is
// where it is (something seen since, beside it, does not keep it there).
constexpr double kStartZone = 0.3;  // [m]

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 1e-12 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace

void OwnTrack::add(const Eigen::Vector2d& at, double clearance)
{
  if (!points_.empty()) {
    const double moved = (at - points_.back().at).norm();
    if (moved > 10.0 * options_.spacing) points_.clear();
    else if (moved < options_.spacing) return;
  }
  points_.push_back({at, clearance});
  // Drop the oldest beyond max_length.
  double length = 0.0;
  for (size_t i = points_.size() - 1; i > 0; --i) {
    length += (points_[i].at - points_[i - 1].at).norm();
    if (length > options_.max_length) {
      points_.erase(points_.begin(), points_.begin() + static_cast<std::ptrdiff_t>(i - 1));
      break;
    }
  }
}

std::optional<WayBack> way_back(const OwnTrack& track, const LocalMap& map, const Eigen::Vector2d& here,
                              double robot_radius, double clearance, const OwnTrackOptions& o)
{
  const auto& pts = track.points();
  if (pts.size() < 2) return std::nullopt;
  // Join the track at its newest point near the robot.
  size_t k = pts.size();
  while (k > 0 && (pts[k - 1].at - here).norm() > kOnTrack) --k;
  if (k == 0) return std::nullopt;
  const double floor = robot_radius + o.min_clearance;
  const double c0 = map.clearance(here, clearance);
  auto need = [&](const TrackPoint& p, double s) {
    double n = std::min(clearance, p.clearance - o.tolerance);
    if (s <= kStartZone) n = std::min(n, c0 - 0.01);
    return std::max(floor, n);
  };
  // Walk back point by point (spacing apart: the body between two of them is covered).
  std::vector<Eigen::Vector2d> path{here};
  std::vector<size_t> index{k};  // the track point each path point is (k: the robot)
  std::vector<double> needs{0.0};
  // The way back leads out of what is tight now (the full clearance counts only once past
  // that: a wider spot inside a pocket is still inside).
  bool tight = c0 < clearance;
  double s = 0.0, clear_for = -1.0;  // [m] driven with the full clearance now, past the tight part (-1: not yet)
  for (size_t i = k; i-- > 0;) {
    const double step = (pts[i].at - path.back()).norm();
    const double now = map.clearance(pts[i].at, clearance);
    if (now < need(pts[i], s + step)) break;
    s += step;
    path.push_back(pts[i].at);
    index.push_back(i);
    needs.push_back(need(pts[i], s));
    if (now < clearance) {
      tight = true;
      clear_for = -1.0;
    } else if (tight) {
      clear_for = clear_for < 0.0 ? 0.0 : clear_for + step;
    }
    if (clear_for >= o.beyond || s >= o.max_back) break;
  }
  // Nothing tight on the way back: the rules that want the full clearance lead out. A way back
  // that stops short of the full clearance (something there now) leads to no place the robot
  // could go on from: no way out either, unless it is max_back long.
  if (!tight || s < o.min_length || (clear_for < 0.0 && s < o.max_back)) return std::nullopt;
  // Straight legs where they stay within kCutCorner of the track points they pass, and keep
  // the body's floor clearance everywhere (a cut corner is not a place the robot has been).
  auto leg_clear = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.025)));
    for (int j = 1; j < n; ++j)
      if (map.clearance(a + (b - a) * (static_cast<double>(j) / n), clearance) < floor) return false;
    return true;
  };
  WayBack out;
  out.length = s;
  size_t a = 0;
  while (a + 1 < path.size()) {
    size_t b = a + 1;
    for (size_t j = a + 2; j < path.size(); ++j) {
      bool straight = true;
      for (size_t m = a + 1; m < j && straight; ++m)
        straight = distance_to_segment(path[m], path[a], path[j]) <= kCutCorner;
      if (!straight || !leg_clear(path[a], path[j])) break;
      b = j;
    }
    out.corners.push_back(path[b]);
    a = b;
  }
  out.track_index = index.back();
  out.points.assign(path.begin() + 1, path.end());
  out.needs.assign(needs.begin() + 1, needs.end());
  return out;
}

}  // namespace rgnav::collision_avoidance
