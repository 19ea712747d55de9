// Labelled gateway data from the simulated worlds (drivers/sim), as in diss. 4.1.4: the
// robot drives toward every crossing from every open side and toward every dead end, with
// random lateral offsets, through the lock-step Simulator; the detector runs on the simulated
// LMS 2xx scans (truth poses as the map frame, like a converged SLAM), and each finished
// observation sequence whose VLM matches the target gateway of the world's ground truth is
// labelled with the class that gateway has from that approach direction. The office world's
// tour gives door detection precision and recall against its ground-truth doors.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <functional>
#include <vector>

#include "gateway_detector/gateway_detector.h"
#include "sim/simulator.h"
#include "sim/world.h"

namespace rgnav::gateway_detector::tools {

// Class (CrossingClass) of ground-truth gateway g when approached travelling along `heading`,
// or -1 if g cannot be approached that way (its entry side is closed) or is no crossing.
int crossing_class_for(const sim::Gateway& g, double heading);

struct Approach
{
  size_t gateway = 0;   // index in world.gateways
  int cls = -1;         // CrossingClass from this direction
  double heading = 0.0; // [rad] travel direction
  sim::Vec2 center;     // of the crossing square, or of the dead end's wall
  double width = 0.0;   // [m] hallway width at the gateway
};
std::vector<Approach> approaches(const sim::World& world);

struct RecordOptions
{
  int repetitions = 6;            // runs per approach
  double approach_length = 7.6;   // [m] start this far before the crossing centre
  double lateral_fraction = 0.2;  // lateral start offset uniform in +- this * width
  double heading_noise = 0.04;    // [rad] std of the start heading error
  double speed = 0.8;             // [m/s]
  double scan_hz = 25.0;          // scans processed per second (the LMS gives 75)
  double match_fraction = 0.35;   // VLM points within this * width of the ground truth
  bool complete_only = true;      // keep sequences that end at the gateway; lost ones are corrupted (4.1.2.3)
  uint64_t seed = 1;
};

struct LabelledSequence
{
  std::string world;
  std::string gateway;
  int cls = -1;
  int run = 0;          // repetition index (even runs train, odd runs test in the benchmark)
  int approach = 0;     // index into approaches(world)
  int64_t group = 0;    // tracker group: the sequences of one run with the same group are
                        // what the detector fuses for one physical gateway
  ObservationSequence sequence;
};

struct RecordStats
{
  int runs = 0;
  int sequences_unmatched = 0;
  int sequences_corrupted = 0;    // matched, but lost before reaching the gateway
  int runs_without_sequence = 0;  // runs that gave no complete matched sequence at all
  std::map<std::string, int> runs_without_sequence_by_approach;  // "<gateway> <class>" -> runs
  std::vector<int> corrupted_lengths;        // observations in each corrupted sequence
  std::vector<double> corrupted_last_distance;  // [m] robot to crossing point when lost
  std::vector<double> kept_first_distance;   // [m] where each kept sequence started
  std::vector<int> kept_lengths;
  std::vector<double> scan_ms;  // detector time per processed scan
};

std::vector<LabelledSequence> record_sequences(const sim::World& world, const DetectorOptions& options,
                                               const RecordOptions& record, RecordStats* stats);

struct DoorEvaluation
{
  int doors_traversed = 0;     // ground-truth doors the robot drove through
  int doors_detected = 0;      // ... of which a reported narrow passage matched before traversal
  int passages_reported = 0;   // approached narrow-passage tracks
  int passages_on_doors = 0;   // ... matching a ground-truth door
  double tour_length = 0.0;    // [m]
  double precision() const { return passages_reported ? static_cast<double>(passages_on_doors) / passages_reported : 0.0; }
  double recall() const { return doors_traversed ? static_cast<double>(doors_detected) / doors_traversed : 0.0; }
  std::vector<std::string> missed;
  // With vision (a second detector on the same scans that also gets the camera's rectangles):
  // passages it classified as doors, how many of those lie on doors, and the door traversals
  // whose passage it had classified as a door before the robot went through.
  int vision_frames = 0;
  int vision_doors_classified = 0;
  int vision_classified_on_doors = 0;
  int vision_doors_detected = 0;
  double vision_precision() const
  {
    return vision_doors_classified ? static_cast<double>(vision_classified_on_doors) / vision_doors_classified : 0.0;
  }
  double vision_recall() const { return doors_traversed ? static_cast<double>(vision_doors_detected) / doors_traversed : 0.0; }
};

// What a camera on the robot sees: its rectangles (base frame at capture) from the robot's true
// pose in the world at a simulation time (the doors' state then), at rate_hz.
struct DoorVision
{
  double rate_hz = 1.0;
  std::function<std::vector<Rectangle3>(const sim::Pose2& truth, const std::vector<uint8_t>& doors_open, int64_t frame)> see;
};

// Drives the world's planned tour (plan_tour) and scores narrow passages against the doors;
// with `vision`, also a detector that gets the camera's rectangles, in the same run.
DoorEvaluation evaluate_doors(const sim::World& world, const DetectorOptions& options, double scan_hz, uint64_t seed,
                              std::vector<double>* scan_ms, const DoorVision* vision = nullptr);

}  // namespace rgnav::gateway_detector::tools
