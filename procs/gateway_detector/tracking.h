// Tracking gateway hypotheses across scans (diss. 4.1.2.3) and the robot's relation to them.
// Crossing hypotheses are the same when all four gateway points match; each track collects an
// observation sequence that starts below a distance threshold and ends when the robot is
// closer than a minimum distance, enters the crossing, or loses the hypothesis. Tracks of one
// physical crossing (different hidden lines) are grouped under the oldest one, which carries
// the events and the fused class probabilities. Narrow passages are tracked by their two
// gateway points. Events: approached -> entered -> traversed, or lost. Map frame throughout.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "gateway_detector/classifiers.h"
#include "gateway_detector/narrow_passage.h"
#include "gateway_detector/vlm.h"

namespace rgnav::gateway_detector {

enum class GatewayKind { kNarrowPassage, kCrossing };
enum class EventKind { kApproached = 1, kEntered = 2, kTraversed = 3, kLost = 4 };

struct TrackingOptions
{
  double crossing_match_distance = 0.5;   // [m] every gateway point closer than this: same VLM
  double passage_match_distance = 0.3;    // [m] both gateway points of a narrow passage
  double group_distance = 0.8;            // [m] crossing points this close: one physical crossing
  double sequence_start_distance = 7.0;   // [m] observations are collected below this distance
  double sequence_end_distance = 1.2;     // [m] ... and down to this one
  double observation_spacing = 0.1;       // [m] robot travel between two observations of a track
  int max_missed = 8;                     // scans without a match before a track is lost ...
  double hold_distance = 1.0;             // [m] ... unless the robot is this close to it (near a
                                          // gateway the scanner no longer sees all of it)
  // ... and unless the robot has moved less than this since the track was last seen: a person
  // walking through the view or clutter passing the beams hides a gateway for a few scans, and
  // what matters is how much of the approach went unobserved, not how many scans (25 or 75 a
  // second). A robot standing still keeps its tracks up to max_missed_stationary scans.
  double lost_travel = 0.0;               // [m]
  int max_missed_stationary = 250;
  int min_observations = 3;               // before a track is reported (approached)
  double enter_distance = 0.3;            // [m] robot centre this close to a passage line: entered
  double exit_margin = 0.1;               // [m] outside a crossing by this much: left it
};

struct Track
{
  int64_t id = 0;
  int64_t group = 0;                 // id of the primary track of its physical gateway
  GatewayKind kind = GatewayKind::kCrossing;
  std::vector<Vec2> points;          // map frame: 2 (left, right) or 4 (VLM order)
  Vec2 axis{1, 0};                   // map frame: direction of approach
  ObservationSequence sequence;      // crossings
  Observation last;                  // newest observation (crossings)
  NarrowPassage last_passage;        // newest detection (narrow passages, laser frame)
  double distance = 0.0;             // [m] robot to crossing point at the last observation
  int seen = 0;                      // scans it was matched in
  int missed = 0;
  bool sequence_closed = false;
  bool approached = false, entered = false, finished = false;
  bool door = false;
  int approach_side = 0;             // narrow passage: side of the line the robot came from
  int entry_side = -1;               // crossing: side index the robot entered through
  Vec2 last_robot{0, 0};             // where the last observation was added
  Vec2 seen_robot{0, 0};             // where the robot was when the track was last matched
  int64_t last_scan = 0;
};

struct TrackEvent
{
  EventKind kind = EventKind::kApproached;
  int64_t track_id = 0;
  GatewayKind gateway = GatewayKind::kCrossing;
  std::vector<Vec2> points;   // map frame
  double direction = 0.0;     // [rad] map frame: heading of the approach / of the crossing
};

// One crossing observation of this scan, already in the map frame.
struct CrossingDetection
{
  std::array<Vec2, 4> points;
  Vec2 axis;
  Observation observation;
};
struct PassageDetection
{
  NarrowPassage passage;      // laser frame
  std::array<Vec2, 2> points; // map frame (left, right)
  Vec2 axis;                  // map frame line of sight
};

struct FinishedSequence
{
  int64_t track_id = 0;
  int64_t group = 0;
  std::array<Vec2, 4> points;
  ObservationSequence sequence;
  bool entered = false;  // closed by reaching the gateway (else lost)
};

class GatewayTracker
{
 public:
  explicit GatewayTracker(const TrackingOptions& options) : options_(options) {}

  // One scan's detections; `robot` = map_from_base. Returns the events it caused.
  std::vector<TrackEvent> update(int64_t scan_id, const geometry::Pose2& robot,
                                 const std::vector<CrossingDetection>& crossings,
                                 const std::vector<PassageDetection>& passages);

  const std::vector<Track>& tracks() const { return tracks_; }
  std::vector<Track>& tracks() { return tracks_; }
  // Crossing sequences that ended since the last call (training, evaluation).
  std::vector<FinishedSequence> take_finished();

 private:
  void close_sequence(Track& t);
  void robot_relation(Track& t, const geometry::Pose2& robot, std::vector<TrackEvent>* events);

  const TrackingOptions options_;
  std::vector<Track> tracks_;
  std::vector<FinishedSequence> finished_;
  int64_t next_id_ = 1;
};

bool point_in_quadrangle(const std::vector<Vec2>& q, const Vec2& p, double margin = 0.0);

}  // namespace rgnav::gateway_detector
