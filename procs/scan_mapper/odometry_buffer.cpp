#include "scan_mapper/odometry_buffer.h"

#include <algorithm>

namespace rgnav::scan_mapper {

void OdometryBuffer::add(const OdometrySample& s)
{
  if (!samples_.empty() && s.utime < samples_.back().utime) return;
  samples_.push_back(s);
  while (samples_.size() > 2 && samples_.front().utime < s.utime - keep_us_) samples_.pop_front();
}

std::optional<Pose2> OdometryBuffer::at(int64_t t, int64_t max_extrapolation_us) const
{
  if (samples_.empty() || t < samples_.front().utime) return std::nullopt;
  if (t >= samples_.back().utime) {
    if (t - samples_.back().utime > max_extrapolation_us) return std::nullopt;
    return samples_.back().odom_from_base;
  }
  // First sample after t; the one before it is at or before t.
  auto hi = std::upper_bound(samples_.begin(), samples_.end(), t,
                             [](int64_t v, const OdometrySample& s) { return v < s.utime; });
  auto lo = std::prev(hi);
  // Equal timestamps: the last sample of that time is the valid one.
  while (std::next(hi) != samples_.end() && std::next(hi)->utime == hi->utime) ++hi;
  if (lo->utime == t) return lo->odom_from_base;
  const double s = static_cast<double>(t - lo->utime) / static_cast<double>(hi->utime - lo->utime);
  return interpolate(lo->odom_from_base, hi->odom_from_base, s);
}

}  // namespace rgnav::scan_mapper
