// Recent odometry samples, interpolated at scan times (scans and odometry are not sampled
// together). Samples with equal timestamps keep arrival order; the last one wins.
#pragma once

#include <deque>
#include <optional>

#include "scan_mapper/scan_types.h"

namespace rgnav::scan_mapper {

class OdometryBuffer
{
 public:
  explicit OdometryBuffer(int64_t keep_us = 5'000'000) : keep_us_(keep_us) {}

  // Samples older than the newest are ignored (a restarted driver resets via clear()).
  void add(const OdometrySample& s);
  void clear() { samples_.clear(); }
  bool empty() const { return samples_.empty(); }
  int64_t newest_utime() const { return samples_.empty() ? 0 : samples_.back().utime; }

  // Pose at t: interpolated between the samples around t; the newest sample if t is at most
  // max_extrapolation_us after it; nullopt if t is outside what the buffer holds.
  std::optional<Pose2> at(int64_t utime, int64_t max_extrapolation_us) const;

 private:
  int64_t keep_us_;
  std::deque<OdometrySample> samples_;
};

}  // namespace rgnav::scan_mapper
