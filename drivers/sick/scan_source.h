// Where the LMS emulator gets its distances from. The simulator plugs its ray caster in;
// tests and the standalone emulator use SyntheticRoom.
#pragma once

#include <cstdint>
#include <vector>

namespace rgnav::drivers::sick {

struct ScanRequest
{
  int64_t utime = 0;               // [us] wall time the first beam is measured
  double angle_min_rad = 0.0;      // bearing of beam 0 in the laser frame (x forward, y left)
  double angle_increment_rad = 0.0;
  int count = 0;
  double scan_time_s = 0.0;        // time from the first to the last beam
};

class ScanSource
{
 public:
  virtual ~ScanSource() = default;
  // Returns `count` ranges in metres. +infinity (or anything beyond the measuring range)
  // means no return; NaN or a negative value means an invalid reading (e.g. dazzle).
  // Called from the emulator's thread.
  virtual std::vector<float> ranges(const ScanRequest& request) = 0;
};

}  // namespace rgnav::drivers::sick
