// The gateway detector for one stream of scans: narrow passages (4.2.1) confirmed as doors by
// 3D rectangles (4.2.2), crossing gateways from VLM hypotheses (4.1.1) with their observation
// vectors (4.1.2), tracking into sequences and events, and classification by the loaded HMMs
// (Bayes fusion over the sequences of one crossing) or, without models, by the observation
// weights. Plain C++: the node adapter converts messages.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <vector>

#include "gateway_detector/door_confirmation.h"
#include "gateway_detector/features.h"
#include "gateway_detector/measures.h"
#include "gateway_detector/narrow_passage.h"
#include "gateway_detector/tracking.h"
#include "gateway_detector/vlm.h"

namespace rgnav::gateway_detector {

// Output classes, in the order of gateway_hypothesis_t::CLASS_* (the node maps them by name).
enum OutputClass {
  kOutUnknown = 0, kOutDoor, kOutNarrowPassage, kOutXCrossing, kOutTCrossing, kOutLTCrossing,
  kOutRTCrossing, kOutLTurn, kOutRTurn, kOutDeadEnd, kOutHallway, kOutOpening, kNumOutputClasses
};
int output_class_of(int crossing_class);
using OutputProbabilities = std::array<double, kNumOutputClasses>;

struct DetectorOptions
{
  FeatureOptions features;
  VlmOptions vlm;
  MeasureOptions measures;
  NarrowPassageOptions narrow_passages;
  DoorConfirmationOptions doors;
  TrackingOptions tracking;
  bool detect_crossings = true;
  bool detect_narrow_passages = true;
};

struct GatewayHypothesis
{
  int64_t track_id = 0;
  int gateway_class = kOutUnknown;
  OutputProbabilities probabilities{};
  std::vector<Vec2> gateway_points;       // base frame
  std::vector<Vec2> crossing_points;      // base frame
  std::vector<double> traversal_directions;  // [rad] base frame
  double distance = 0.0;                  // [m] robot to nearest crossing point
  int observations = 0;
};

struct GatewayEvent
{
  EventKind kind = EventKind::kApproached;
  int64_t track_id = 0;
  int gateway_class = kOutUnknown;
  OutputProbabilities probabilities{};
  geometry::Pose2 map_from_base;
  std::vector<Vec2> gateway_points;  // map frame
  double direction = 0.0;            // [rad] map frame
};

struct DetectorOutput
{
  int64_t utime = 0;
  int64_t scan_id = 0;
  geometry::Pose2 map_from_base;
  std::vector<GatewayHypothesis> hypotheses;
  std::vector<GatewayEvent> events;
};

class GatewayDetector
{
 public:
  explicit GatewayDetector(const DetectorOptions& options, HmmClassifier classifier = {});

  DetectorOutput process(const PosedScan& scan);
  // 3D rectangles seen at map_from_capture (map frame of the scans), kept for door confirmation.
  void add_rectangles(int64_t utime, const geometry::Pose2& map_from_capture, const std::vector<Rectangle3>& rectangles);

  // Per-scan crossing observations, exposed for training and tests.
  std::vector<std::pair<Vlm, Observation>> observe_crossings(const sensors::LaserScan& scan) const;
  std::vector<std::pair<Vlm, Observation>> observe_crossings(const sensors::LaserScan& scan, const ScanFeatures& features) const;
  std::vector<FinishedSequence> take_finished_sequences() { return tracker_.take_finished(); }
  const GatewayTracker& tracker() const { return tracker_; }
  const DetectorOptions& options() const { return options_; }
  bool has_models() const { return !classifier_.empty(); }

 private:
  OutputProbabilities probabilities_of(const Track& primary);

  const DetectorOptions options_;
  const HmmClassifier classifier_;
  GatewayTracker tracker_;
  struct DoorFrame
  {
    std::array<Vec2, 2> edges;  // map frame
    int64_t utime;
  };
  std::vector<DoorFrame> door_frames_;
  struct LikelihoodCache
  {
    size_t length = 0;
    ClassLogLikelihoods ll{};
  };
  std::map<int64_t, LikelihoodCache> cache_;
};

}  // namespace rgnav::gateway_detector
