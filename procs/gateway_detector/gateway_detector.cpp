#include "gateway_detector/gateway_detector.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace rgnav::gateway_detector {

int output_class_of(int c)
{
  switch (c) {
    case kX: return kOutXCrossing;
    case kT: return kOutTCrossing;
    case kLT: return kOutLTCrossing;
    case kRT: return kOutRTCrossing;
    case kLTurn: return kOutLTurn;
    case kRTurn: return kOutRTurn;
    case kDeadEnd: return kOutDeadEnd;
    case kHallway: return kOutHallway;
    default: return kOutUnknown;
  }
}

GatewayDetector::GatewayDetector(const DetectorOptions& options, HmmClassifier classifier)
    : options_(options), classifier_(std::move(classifier)), tracker_(options.tracking)
{
}

std::vector<std::pair<Vlm, Observation>> GatewayDetector::observe_crossings(const sensors::LaserScan& scan) const
{
  return observe_crossings(scan, extract_features(scan, options_.features));
}

std::vector<std::pair<Vlm, Observation>> GatewayDetector::observe_crossings(const sensors::LaserScan& scan, const ScanFeatures& f) const
{
  std::vector<std::pair<Vlm, Observation>> out;
  for (const Vlm& v : group_vlms(f, options_.vlm)) {
    Observation o;
    o.measures = measure(scan, v, options_.measures);
    o.weights = class_weights(o.measures, options_.measures);
    o.distance = v.crossing_point().norm();
    out.push_back({v, o});
  }
  return out;
}

void GatewayDetector::add_rectangles(int64_t utime, const geometry::Pose2& map_from_capture, const std::vector<Rectangle3>& rects)
{
  for (const auto& r : rects) {
    const auto e = door_edges(r, options_.doors);
    if (!e) continue;
    door_frames_.push_back({{map_from_capture * (*e)[0], map_from_capture * (*e)[1]}, utime});
  }
  const auto horizon = utime - static_cast<int64_t>(options_.doors.memory_s * 1e6);
  door_frames_.erase(std::remove_if(door_frames_.begin(), door_frames_.end(), [&](const DoorFrame& d) { return d.utime < horizon; }),
                     door_frames_.end());
}

OutputProbabilities GatewayDetector::probabilities_of(const Track& primary)
{
  OutputProbabilities out{};
  if (primary.kind == GatewayKind::kNarrowPassage) {
    out[primary.door ? kOutDoor : kOutNarrowPassage] = 1.0;
    return out;
  }
  ClassProbabilities p{};
  if (!classifier_.empty()) {
    std::vector<ClassLogLikelihoods> lls;
    for (const auto& t : tracker_.tracks()) {
      if (t.group != primary.id || t.kind != GatewayKind::kCrossing || t.sequence.empty()) continue;
      auto& c = cache_[t.id];
      if (c.length != t.sequence.size()) {
        c.ll = classifier_.log_likelihoods(t.sequence);
        c.length = t.sequence.size();
      }
      lls.push_back(c.ll);
    }
    p = lls.empty() ? weights_to_probabilities(primary.last.weights) : fuse(lls);
  } else {
    p = weights_to_probabilities(primary.last.weights);
  }
  for (int c = 0; c < kNumSequenceClasses; ++c) out[output_class_of(c)] = p[c];
  return out;
}

DetectorOutput GatewayDetector::process(const PosedScan& ps)
{
  DetectorOutput out;
  out.utime = ps.scan.utime;
  out.scan_id = ps.scan.scan_id;
  out.map_from_base = ps.map_from_base;
  const geometry::Pose2 map_from_laser = ps.map_from_laser();

  const ScanFeatures features = extract_features(ps.scan, options_.features);
  std::vector<CrossingDetection> crossings;
  if (options_.detect_crossings) {
    for (const auto& [v, o] : observe_crossings(ps.scan, features)) {
      CrossingDetection d;
      for (int k = 0; k < 4; ++k) d.points[static_cast<size_t>(k)] = map_from_laser * v.points[static_cast<size_t>(k)];
      d.axis = map_from_laser.rotation() * v.axis;
      d.observation = o;
      crossings.push_back(d);
    }
  }
  std::vector<PassageDetection> passages;
  if (options_.detect_narrow_passages) {
    auto found = detect_narrow_passages(ps.scan, options_.narrow_passages);
    if (options_.narrow_passages.wall_gaps) {
      for (const auto& g : detect_wall_gaps(ps.scan, features, options_.narrow_passages)) {
        const bool dup = std::any_of(found.begin(), found.end(), [&](const NarrowPassage& n) {
          return (n.left - g.left).norm() < 0.2 && (n.right - g.right).norm() < 0.2;
        });
        if (!dup) found.push_back(g);
      }
    }
    for (const auto& np : found) {
      PassageDetection d;
      d.passage = np;
      d.points = {map_from_laser * np.left, map_from_laser * np.right};
      d.axis = map_from_laser.rotation() * Vec2(std::cos(np.viewing_direction), std::sin(np.viewing_direction));
      passages.push_back(d);
    }
  }
  const auto events = tracker_.update(ps.scan.scan_id, ps.map_from_base, crossings, passages);

  // Door confirmation of the tracked passages.
  for (auto& t : tracker_.tracks()) {
    if (t.kind != GatewayKind::kNarrowPassage || t.door) continue;
    for (const auto& d : door_frames_)
      if (edges_match(d.edges, t.points[0], t.points[1], options_.doors.match_distance)) t.door = true;
  }

  const geometry::Pose2 base_from_map = ps.map_from_base.inverse();
  std::map<int64_t, OutputProbabilities> probs;
  for (const auto& t : tracker_.tracks()) {
    if (t.group != t.id) continue;
    probs[t.id] = probabilities_of(t);
  }
  auto best_of = [](const OutputProbabilities& p) { return static_cast<int>(std::max_element(p.begin(), p.end()) - p.begin()); };

  for (const auto& t : tracker_.tracks()) {
    if (t.group != t.id || t.finished || !t.approached || t.missed > 0 || t.last_scan != ps.scan.scan_id) continue;
    GatewayHypothesis h;
    h.track_id = t.id;
    h.probabilities = probs[t.id];
    h.gateway_class = best_of(h.probabilities);
    for (const auto& p : t.points) h.gateway_points.push_back(base_from_map * p);
    const Vec2 axis_base = base_from_map.rotation() * t.axis;
    if (t.kind == GatewayKind::kNarrowPassage) {
      h.crossing_points.push_back(0.5 * (h.gateway_points[0] + h.gateway_points[1]));
      h.traversal_directions = {std::atan2(axis_base.y(), axis_base.x()), std::atan2(-axis_base.y(), -axis_base.x())};
    } else {
      // Crossing points: middles of the entry and of every side the class leaves open.
      int cls = kX;
      for (int c = 0; c < kNumSequenceClasses; ++c)
        if (output_class_of(c) == h.gateway_class) cls = c;
      const auto& g = h.gateway_points;
      h.crossing_points.push_back(0.5 * (g[3] + g[0]));
      h.traversal_directions.push_back(std::atan2(-axis_base.y(), -axis_base.x()));
      const Vec2 left_dir(-axis_base.y(), axis_base.x());
      const Vec2 dirs[3] = {left_dir, axis_base, -left_dir};
      for (int s = 0; s < 3; ++s) {
        if (!expects_open(cls, s)) continue;
        h.crossing_points.push_back(0.5 * (g[static_cast<size_t>(s)] + g[static_cast<size_t>(s + 1)]));
        h.traversal_directions.push_back(std::atan2(dirs[s].y(), dirs[s].x()));
      }
    }
    h.distance = std::numeric_limits<double>::infinity();
    for (const auto& c : h.crossing_points) h.distance = std::min(h.distance, c.norm());
    h.observations = t.kind == GatewayKind::kCrossing ? static_cast<int>(t.sequence.size()) : t.seen;
    out.hypotheses.push_back(std::move(h));
  }
  for (const auto& e : events) {
    GatewayEvent ge;
    ge.kind = e.kind;
    ge.track_id = e.track_id;
    ge.map_from_base = ps.map_from_base;
    ge.gateway_points = e.points;
    ge.direction = e.direction;
    const auto it = probs.find(e.track_id);
    if (it != probs.end()) {
      ge.probabilities = it->second;
      ge.gateway_class = best_of(it->second);
    } else {
      ge.gateway_class = e.gateway == GatewayKind::kNarrowPassage ? kOutNarrowPassage : kOutUnknown;
      ge.probabilities[ge.gateway_class] = 1.0;
    }
    out.events.push_back(std::move(ge));
  }
  // Forget cached likelihoods of tracks that are gone.
  std::set<int64_t> live;
  for (const auto& t : tracker_.tracks()) live.insert(t.id);
  for (auto it = cache_.begin(); it != cache_.end();) it = live.count(it->first) ? std::next(it) : cache_.erase(it);
  return out;
}

}  // namespace rgnav::gateway_detector
