#include "gateway_detector/tracking.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/segment2.h"

namespace rgnav::gateway_detector {

namespace {

// Outward signed distance of p from side i of a convex polygon (positive = outside).
double side_distance(const std::vector<Vec2>& q, size_t i, const Vec2& p)
{
  Vec2 c = Vec2::Zero();
  for (const auto& v : q) c += v;
  c /= static_cast<double>(q.size());
  const Vec2 a = q[i], b = q[(i + 1) % q.size()];
  Vec2 n(-(b - a).y(), (b - a).x());
  if (n.norm() < 1e-9) return -std::numeric_limits<double>::infinity();
  n.normalize();
  if (n.dot(c - a) > 0) n = -n;
  return n.dot(p - a);
}

int outside_side(const std::vector<Vec2>& q, const Vec2& p, double margin)
{
  int best = -1;
  double bd = margin;
  for (size_t i = 0; i < q.size(); ++i) {
    const double d = side_distance(q, i, p);
    if (d > bd) {
      bd = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

Vec2 centroid(const std::vector<Vec2>& q)
{
  Vec2 c = Vec2::Zero();
  for (const auto& v : q) c += v;
  return c / static_cast<double>(q.size());
}

int side_of(const Vec2& a, const Vec2& b, const Vec2& p)
{
  const Vec2 ab = b - a, ap = p - a;
  return ab.x() * ap.y() - ab.y() * ap.x() >= 0 ? 1 : -1;
}

double heading(const Vec2& v) { return std::atan2(v.y(), v.x()); }

}  // namespace

bool point_in_quadrangle(const std::vector<Vec2>& q, const Vec2& p, double margin)
{
  return outside_side(q, p, margin) < 0;
}

void GatewayTracker::close_sequence(Track& t)
{
  if (t.kind != GatewayKind::kCrossing || t.sequence_closed) return;
  t.sequence_closed = true;
  if (t.sequence.empty()) return;
  FinishedSequence f;
  f.track_id = t.id;
  f.group = t.group;
  for (int i = 0; i < 4; ++i) f.points[static_cast<size_t>(i)] = t.points[static_cast<size_t>(i)];
  f.sequence = t.sequence;
  f.entered = t.entered || t.distance <= options_.sequence_end_distance;
  finished_.push_back(std::move(f));
}

std::vector<FinishedSequence> GatewayTracker::take_finished()
{
  std::vector<FinishedSequence> out;
  out.swap(finished_);
  return out;
}

std::vector<TrackEvent> GatewayTracker::update(int64_t scan_id, const geometry::Pose2& robot,
                                               const std::vector<CrossingDetection>& crossings,
                                               const std::vector<PassageDetection>& passages)
{
  std::vector<TrackEvent> events;
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(), [](const Track& t) { return t.finished; }), tracks_.end());
  const Vec2 rp = robot.translation();

  // Greedy assignment by the worst gateway point distance.
  struct Pair
  {
    double cost;
    size_t track, det;
  };
  std::vector<Pair> pairs;
  for (size_t ti = 0; ti < tracks_.size(); ++ti) {
    const Track& t = tracks_[ti];
    if (t.entered || t.finished) continue;
    if (t.kind == GatewayKind::kCrossing) {
      for (size_t di = 0; di < crossings.size(); ++di) {
        double worst = 0.0;
        for (int k = 0; k < 4; ++k) worst = std::max(worst, (t.points[static_cast<size_t>(k)] - crossings[di].points[static_cast<size_t>(k)]).norm());
        if (worst < options_.crossing_match_distance) pairs.push_back({worst, ti, di});
      }
    } else {
      for (size_t di = 0; di < passages.size(); ++di) {
        const double worst = std::max((t.points[0] - passages[di].points[0]).norm(), (t.points[1] - passages[di].points[1]).norm());
        if (worst < options_.passage_match_distance) pairs.push_back({worst, ti, crossings.size() + di});
      }
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.cost < b.cost; });
  std::vector<int> track_det(tracks_.size(), -1);
  std::vector<bool> det_used(crossings.size() + passages.size(), false);
  for (const auto& p : pairs) {
    if (track_det[p.track] >= 0 || det_used[p.det]) continue;
    track_det[p.track] = static_cast<int>(p.det);
    det_used[p.det] = true;
  }

  auto observe_crossing = [&](Track& t, const CrossingDetection& d) {
    t.points.assign(d.points.begin(), d.points.end());
    t.axis = d.axis;
    t.last = d.observation;
    t.distance = d.observation.distance;
    ++t.seen;
    t.missed = 0;
    t.last_scan = scan_id;
    t.seen_robot = rp;
    if (!t.sequence_closed && t.distance <= options_.sequence_start_distance &&
        (t.sequence.empty() || (rp - t.last_robot).norm() >= options_.observation_spacing)) {
      t.sequence.push_back(d.observation);
      t.last_robot = rp;
    }
    if (t.distance <= options_.sequence_end_distance) close_sequence(t);
  };
  auto observe_passage = [&](Track& t, const PassageDetection& d) {
    t.points.assign(d.points.begin(), d.points.end());
    t.axis = d.axis;
    t.last_passage = d.passage;
    t.distance = (0.5 * (d.points[0] + d.points[1]) - rp).norm();
    ++t.seen;
    t.missed = 0;
    t.last_scan = scan_id;
    t.seen_robot = rp;
  };

  const size_t old_count = tracks_.size();
  for (size_t ti = 0; ti < old_count; ++ti) {
    Track& t = tracks_[ti];
    if (t.entered || t.finished) continue;
    if (track_det[ti] < 0) {
      const double gap = t.kind == GatewayKind::kNarrowPassage
                             ? geometry::point_segment_distance(rp, t.points[0], t.points[1])
                             : std::max(0.0, side_distance(t.points, static_cast<size_t>(std::max(0, outside_side(t.points, rp, 0.0))), rp));
      const bool moved_on = (rp - t.seen_robot).norm() >= options_.lost_travel || t.missed >= options_.max_missed_stationary;
      if (++t.missed > options_.max_missed && gap > options_.hold_distance && moved_on) {
        close_sequence(t);
        if (t.approached && t.group == t.id)
          events.push_back({EventKind::kLost, t.id, t.kind, t.points, heading(t.axis)});
        t.finished = true;
      }
      continue;
    }
    const auto di = static_cast<size_t>(track_det[ti]);
    if (t.kind == GatewayKind::kCrossing) observe_crossing(t, crossings[di]);
    else observe_passage(t, passages[di - crossings.size()]);
  }
  // A detection of a gateway the robot is already in belongs to that gateway's frozen track.
  auto inside_known = [&](const std::vector<Vec2>& pts, GatewayKind kind, double tol) {
    for (const auto& t : tracks_) {
      if (!t.entered || t.finished || t.kind != kind) continue;
      if (kind == GatewayKind::kCrossing && (centroid(t.points) - centroid(pts)).norm() < options_.group_distance) return true;
      if (kind == GatewayKind::kNarrowPassage &&
          std::min(std::max((t.points[0] - pts[0]).norm(), (t.points[1] - pts[1]).norm()),
                   std::max((t.points[0] - pts[1]).norm(), (t.points[1] - pts[0]).norm())) < tol)
        return true;
    }
    return false;
  };
  // New tracks.
  for (size_t di = 0; di < crossings.size(); ++di) {
    if (det_used[di] || crossings[di].observation.distance > options_.sequence_start_distance) continue;
    if (inside_known({crossings[di].points.begin(), crossings[di].points.end()}, GatewayKind::kCrossing, 0.0)) continue;
    Track t;
    t.id = next_id_++;
    t.kind = GatewayKind::kCrossing;
    t.group = t.id;
    const Vec2 c = centroid({crossings[di].points.begin(), crossings[di].points.end()});
    for (const auto& o : tracks_) {
      if (o.finished || o.kind != GatewayKind::kCrossing || o.group != o.id) continue;
      if ((centroid(o.points) - c).norm() < options_.group_distance) {
        t.group = o.id;
        break;
      }
    }
    observe_crossing(t, crossings[di]);
    tracks_.push_back(std::move(t));
  }
  for (size_t k = 0; k < passages.size(); ++k) {
    if (det_used[crossings.size() + k]) continue;
    if (inside_known({passages[k].points[0], passages[k].points[1]}, GatewayKind::kNarrowPassage, 2 * options_.passage_match_distance))
      continue;
    Track t;
    t.id = next_id_++;
    t.group = t.id;
    t.kind = GatewayKind::kNarrowPassage;
    observe_passage(t, passages[k]);
    tracks_.push_back(std::move(t));
  }
  // A group whose primary is gone: each member stands on its own.
  for (auto& t : tracks_) {
    if (t.group == t.id) continue;
    const auto it = std::find_if(tracks_.begin(), tracks_.end(), [&](const Track& o) { return o.id == t.group; });
    if (it == tracks_.end() || (it->finished && !it->entered)) t.group = t.id;
  }
  for (auto& t : tracks_)
    if (!t.finished && t.group == t.id) robot_relation(t, robot, &events);
  // Members follow their primary into the gateway.
  for (auto& t : tracks_) {
    if (t.group == t.id || t.finished) continue;
    const auto it = std::find_if(tracks_.begin(), tracks_.end(), [&](const Track& o) { return o.id == t.group; });
    if (it != tracks_.end() && (it->entered || it->finished)) {
      t.finished = it->finished;
      t.entered = it->entered;
      close_sequence(t);
    }
  }
  return events;
}

void GatewayTracker::robot_relation(Track& t, const geometry::Pose2& robot, std::vector<TrackEvent>* events)
{
  const Vec2 rp = robot.translation();
  auto emit = [&](EventKind k, double dir) { events->push_back({k, t.id, t.kind, t.points, dir}); };
  if (!t.approached) {
    if (t.seen < options_.min_observations || t.missed > 0) return;
    if (t.kind == GatewayKind::kCrossing && t.distance > options_.sequence_start_distance) return;
    t.approached = true;
    if (t.kind == GatewayKind::kNarrowPassage) t.approach_side = side_of(t.points[0], t.points[1], rp);
    emit(EventKind::kApproached, heading(t.axis));
  }
  if (t.kind == GatewayKind::kNarrowPassage) {
    const double d = geometry::point_segment_distance(rp, t.points[0], t.points[1]);
    const int side = side_of(t.points[0], t.points[1], rp);
    if (!t.entered) {
      if (d < options_.enter_distance) {
        t.entered = true;
        emit(EventKind::kEntered, robot.theta());
      }
    } else if (d > options_.enter_distance) {
      emit(side != t.approach_side ? EventKind::kTraversed : EventKind::kLost, robot.theta());
      t.finished = true;
    }
    return;
  }
  if (!t.entered) {
    if (point_in_quadrangle(t.points, rp)) {
      t.entered = true;
      close_sequence(t);
      emit(EventKind::kEntered, robot.theta());
    }
  } else {
    const int exit = outside_side(t.points, rp, options_.exit_margin);
    if (exit >= 0) {
      // Side 3 is the entry side: leaving through it is turning back.
      emit(exit != 3 ? EventKind::kTraversed : EventKind::kLost, robot.theta());
      t.finished = true;
    }
  }
}

}  // namespace rgnav::gateway_detector
