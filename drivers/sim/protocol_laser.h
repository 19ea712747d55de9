// The simulator as the LMS 2xx emulator's ScanSource in protocol mode. The emulator runs in
// its own thread on the wall clock (it models the serial line and the mirror in real time)
// and asks for each scan's ranges at the wall time of its first beam; in protocol mode the
// simulator's message time follows the wall clock, so that is also a simulated instant.
// The simulator thread records the scene state after every physics step (base pose, doors,
// people) into a short history; ranges() ray-casts from the recorded state nearest the
// requested time, for whatever variant (100/180 deg, 1/0.5/0.25 deg) the driver configured,
// and adds the simulator's range noise (the emulator quantises to the configured units).
//
// Thread-safe: record() from the simulator's thread, ranges() from the emulator's. The Scene
// is shared read-only and must outlive this object.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <mutex>
#include <vector>

#include "sick/scan_source.h"
#include "sim/lms2xx_model.h"
#include "sim/rng.h"
#include "sim/scene.h"
#include "sim/simulator.h"

namespace rgnav::sim {

// What the laser sees at one instant.
struct LaserSceneState
{
  int64_t utime = 0;     // [us] simulated message time
  Pose2 world_from_base;
  std::vector<uint8_t> door_open;
  std::vector<Circle> people;
};

// Ranges [m] of `count` beams from angle_min in steps of `increment` (laser frame), cast in
// the scan plane at `mount_height` from `laser_pose`; +infinity where nothing lies within
// max_range. The general form of Lms2xxModel::true_ranges for any LMS variant.
std::vector<double> cast_beams(const Scene& scene, const LaserSceneState& state, const Pose2& laser_pose,
                               double angle_min, double increment, int count, double mount_height,
                               double max_range);

class SimScanSource final : public drivers::sick::ScanSource
{
 public:
  // `laser`: mounting and noise from the simulator's options (its beam count and range mode
  // are the direct mode's; here the driver's configuration of the emulated device rules).
  SimScanSource(const Scene& scene, const Lms2xxOptions& laser, Rng rng,
                std::chrono::microseconds history = std::chrono::milliseconds(500));

  void record(LaserSceneState state);
  void record(const Simulator& sim);
  std::vector<float> ranges(const drivers::sick::ScanRequest& request) override;

  // The recorded state nearest `utime` (the oldest/newest outside the history).
  LaserSceneState state_at(int64_t utime) const;
  uint64_t scans_served() const;

 private:
  const Scene& scene_;
  // A model only for its laser_pose(): mounting is the simulator's.
  const Lms2xxModel model_;
  const double noise_sigma_;
  const int64_t history_us_;
  mutable std::mutex mutex_;
  std::deque<LaserSceneState> states_;
  Rng rng_;
  uint64_t served_ = 0;
};

}  // namespace rgnav::sim
