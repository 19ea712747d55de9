#include "collision_avoidance/people_tracker.h"

#include <algorithm>
#include <limits>

namespace rgnav::collision_avoidance {

std::vector<std::vector<Eigen::Vector2d>> PeopleTracker::clusters(const std::vector<Eigen::Vector2d>& points) const
{
  // Single linkage by flood fill: a scan has few moving points (tens), quadratic is fine.
  std::vector<std::vector<Eigen::Vector2d>> out;
  std::vector<char> used(points.size(), 0);
  const double d2 = options_.cluster_distance * options_.cluster_distance;
  for (size_t i = 0; i < points.size(); ++i) {
    if (used[i]) continue;
    std::vector<size_t> members{i};
    used[i] = 1;
    for (size_t k = 0; k < members.size(); ++k)
      for (size_t j = 0; j < points.size(); ++j)
        if (!used[j] && (points[j] - points[members[k]]).squaredNorm() <= d2) {
          used[j] = 1;
          members.push_back(j);
        }
    if (static_cast<int>(members.size()) < options_.min_points) continue;
    std::vector<Eigen::Vector2d> c;
    for (size_t m : members) c.push_back(points[m]);
    out.push_back(std::move(c));
  }
  return out;
}

void PeopleTracker::fit_velocity(Track& t) const
{
  t.velocity.setZero();
  if (t.centroids.size() < 3) return;
  const time::Time t0 = t.centroids.front().first;
  double st = 0, stt = 0;
  Eigen::Vector2d sp = Eigen::Vector2d::Zero(), stp = Eigen::Vector2d::Zero();
  for (const auto& [stamp, c] : t.centroids) {
    const double x = time::to_seconds(stamp - t0);
    st += x;
    stt += x * x;
    sp += c;
    stp += x * c;
  }
  const double n = static_cast<double>(t.centroids.size());
  const double den = n * stt - st * st;
  if (den < 1e-9) return;
  t.velocity = (n * stp - st * sp) / den;
}

bool PeopleTracker::left_its_place(const Track& t, const SeenNowFn& seen_now) const
{
  if (!seen_now || t.clusters.size() < 2) return true;
  int known = 0, still = 0;
  for (const auto& p : t.clusters.front()) {
    const SeenNow s = seen_now(p);
    if (s == SeenNow::kUnknown) continue;
    ++known;
    if (s == SeenNow::kStillThere) ++still;
  }
  return known == 0 || still <= options_.max_still_there * known;
}

void PeopleTracker::update(time::Time stamp, const std::vector<Eigen::Vector2d>& moving_points,
                           const SeenNowFn& seen_now, bool robot_turning)
{
  std::vector<char> continued(tracks_.size(), 0);
  for (auto& cluster : clusters(moving_points)) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const auto& p : cluster) c += p;
    c /= static_cast<double>(cluster.size());
    // The nearest track (by its constant-velocity prediction) not yet continued this scan.
    int best = -1;
    double best_d = options_.gate;
    for (size_t i = 0; i < tracks_.size(); ++i) {
      if (continued[i]) continue;
      const Track& t = tracks_[i];
      const Eigen::Vector2d pred = t.centroids.back().second + t.velocity * time::to_seconds(stamp - t.last_seen);
      const double d = (pred - c).norm();
      if (d < best_d) {
        best_d = d;
        best = static_cast<int>(i);
      }
    }
    if (best < 0) {
      Track fresh;
      fresh.id = next_id_++;
      fresh.last_seen = stamp;
      tracks_.push_back(std::move(fresh));
      continued.push_back(0);
      best = static_cast<int>(tracks_.size()) - 1;
    }
    Track& t = tracks_[static_cast<size_t>(best)];
    continued[static_cast<size_t>(best)] = 1;
    const double since_seen = t.centroids.empty() ? 0.0 : time::to_seconds(stamp - t.last_seen);
    const bool was_predicting = !t.centroids.empty() && predicts(t);
    if (t.centroids.empty()) t.first = c;
    t.travelled = std::max(t.travelled, (c - t.first).norm());
    t.centroids.emplace_back(stamp, c);
    t.clusters.push_back(std::move(cluster));
    while (time::to_seconds(stamp - t.centroids.front().first) > options_.history) {
      t.centroids.pop_front();
      t.clusters.pop_front();
    }
    t.last_seen = stamp;
    fit_velocity(t);
    t.left_its_place = left_its_place(t, seen_now);
    if (predicts(t)) {
      t.moved = true;
      t.walking = t.velocity;
      if (was_predicting) t.moving_for += since_seen;
      if (was_predicting && !robot_turning) t.moving_steady += since_seen;
    }
  }
  auto lost = [&](const Track& t) { return time::to_seconds(stamp - t.last_seen) > options_.lost_after; };
  for (const Track& t : tracks_)
    if (lost(t) && t.moved && t.travelled >= options_.stopped_min_travel && t.moving_for >= options_.stopped_min_moving)
      last_seen_.push_back({t.last_seen, t.centroids.back().second, t.walking, t.moving_steady, t.first});
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(), lost), tracks_.end());
  while (!last_seen_.empty() && time::to_seconds(stamp - last_seen_.front().stamp) > options_.stopped_memory)
    last_seen_.pop_front();
}

bool PeopleTracker::predicts(const Track& t) const
{
  // A track needs most of its history before its velocity means anything.
  if (t.centroids.size() < 3 ||
      time::to_seconds(t.centroids.back().first - t.centroids.front().first) < 0.5 * options_.history)
    return false;
  const double speed = t.velocity.norm();
  return speed >= options_.min_speed && speed <= options_.max_speed && t.left_its_place;
}

std::vector<Eigen::Vector2d> PeopleTracker::predicted(time::Time now) const
{
  std::vector<Eigen::Vector2d> out;
  for (const Track& t : tracks_) {
    if (!predicts(t)) continue;
    const double since = time::to_seconds(now - t.last_seen);
    for (double dt = options_.step; dt <= options_.horizon + 1e-9; dt += options_.step) {
      const Eigen::Vector2d shift = t.velocity * (since + dt);
      for (const auto& p : t.clusters.back()) out.push_back(p + shift);
    }
  }
  return out;
}

}  // namespace rgnav::collision_avoidance
