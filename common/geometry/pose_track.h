// Poses sampled in time (a simulator's ground truth, odometry) and the pose between two samples.
// One helper for every evaluation that compares an estimate with the truth at a scan's time.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

#include "geometry/pose2.h"

namespace rgnav::geometry {

// Linear interpolation of poses (shortest way round in theta), s in [0, 1].
inline Pose2 interpolate(const Pose2& a, const Pose2& b, double s)
{
  return Pose2(a.x() + s * (b.x() - a.x()), a.y() + s * (b.y() - a.y()), a.theta() + s * normalize_angle(b.theta() - a.theta()));
}

// The pose at `utime` from time-sorted samples (a random-access container; pose_of reads a
// sample's pose, each has .utime): the sample at that time, else interpolated between the two
// around it when both lie within max_gap_us of it; nothing before the first, after the last or
// across a longer gap. What a node needs to place an input between the odometry around it.
template <class Samples, class PoseOf>
std::optional<Pose2> bracketed_at(const Samples& samples, int64_t utime, int64_t max_gap_us, const PoseOf& pose_of)
{
  const auto after = std::lower_bound(samples.begin(), samples.end(), utime,
                                      [](const auto& s, int64_t t) { return s.utime < t; });
  if (after == samples.end()) return std::nullopt;
  if (after->utime == utime) return pose_of(*after);
  if (after == samples.begin()) return std::nullopt;
  const auto& a = *(after - 1);
  const auto& b = *after;
  if (utime - a.utime > max_gap_us || b.utime - utime > max_gap_us) return std::nullopt;
  const double s = static_cast<double>(utime - a.utime) / static_cast<double>(b.utime - a.utime);
  return interpolate(pose_of(a), pose_of(b), s);
}

class PoseTrack
{
 public:
  // Samples come in time order; of two at one time, the later added is the one read.
  void add(int64_t utime, const Pose2& pose) { samples_.push_back({utime, pose}); }
  bool empty() const { return samples_.empty(); }

  // The pose at utime: the sample at that time, else interpolated between the two around it,
  // else (after the last sample) the last one; nullopt before the first sample.
  std::optional<Pose2> at(int64_t utime) const
  {
    auto after = std::upper_bound(samples_.begin(), samples_.end(), utime,
                                  [](int64_t u, const Sample& s) { return u < s.utime; });
    if (after == samples_.begin()) return std::nullopt;
    const Sample& a = *(after - 1);
    if (a.utime == utime || after == samples_.end()) return a.pose;
    const Sample& b = *after;
    const double s = static_cast<double>(utime - a.utime) / static_cast<double>(b.utime - a.utime);
    return interpolate(a.pose, b.pose, s);
  }

  // As at(), but before the first sample the first one (nullopt only when empty).
  std::optional<Pose2> clamped_at(int64_t utime) const
  {
    if (samples_.empty()) return std::nullopt;
    if (utime < samples_.front().utime) return samples_.front().pose;
    return at(utime);
  }

 private:
  struct Sample
  {
    int64_t utime;
    Pose2 pose;
  };
  std::vector<Sample> samples_;
};

}  // namespace rgnav::geometry
