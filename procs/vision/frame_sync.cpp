#include "vision/frame_sync.h"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include "geometry/pose_track.h"

namespace rgnav::vision {

namespace {

// Odometry kept: a few seconds cover any frame that can still be processed.
constexpr int64_t kKeepOdometryUs = 3'000'000;

}  // namespace

FrameSync::FrameSync(VisionPipeline& pipeline, const FrameSyncOptions& options, FrameSyncCallbacks callbacks)
    : pipeline_(pipeline),
      options_(options),
      callbacks_(std::move(callbacks)),
      max_gap_us_(static_cast<int64_t>(std::llround(options.max_pose_gap * 1e6))),
      laser_period_us_(static_cast<int64_t>(std::llround(options.laser_period * 1e6)))
{
}

bool FrameSync::on_odometry(int64_t utime, int64_t seq, const geometry::Pose2& odom_from_base)
{
  // The base driver publishes at its own rate: a message with no new encoder sample since the
  // last repeats that sample's stamp (a loaded host delays the drives' samples). It adds nothing,
  // and is no restart: taking it for one emptied the map of the table tops it held.
  const bool repeat = !odometry_.empty() && utime == odometry_.back().utime && seq > last_odometry_seq_;
  if (repeat) {
    last_odometry_seq_ = seq;
    return false;
  }
  const bool restarted = !odometry_.empty() && (utime < odometry_.back().utime || seq < last_odometry_seq_);
  if (restarted) {
    // A new odometry frame: the map's coordinates mean nothing in it.
    spdlog::warn("odometry went back (seq {} -> {}): the map starts afresh", last_odometry_seq_, seq);
    odometry_.clear();
    pipeline_.reset_map();
    pending_laser_.reset();
    last_laser_utime_ = 0;
    ++resets_;
  }
  last_odometry_seq_ = seq;
  odometry_.push_back({utime, odom_from_base});
  while (odometry_.size() > 2 && odometry_[1].utime < utime - kKeepOdometryUs) odometry_.pop_front();
  try_frame();
  try_laser();
  return restarted;
}

void FrameSync::on_frame(StereoFrame frame)
{
  if (pending_frame_) ++superseded_;   // its odometry never came in time; the newer one is worth more
  pending_frame_ = std::move(frame);
  try_frame();
}

void FrameSync::on_laser(sensors::LaserScan scan)
{
  if (last_laser_utime_ != 0 && scan.utime > last_laser_utime_ && scan.utime - last_laser_utime_ < laser_period_us_) return;
  pending_laser_ = std::move(scan);
  try_laser();
}

double FrameSync::odometry_lead_s(int64_t utime) const
{
  return odometry_.empty() ? 0.0 : static_cast<double>(odometry_.back().utime - utime) * 1e-6;
}

std::optional<geometry::Pose2> FrameSync::odometry_at(int64_t utime) const
{
  return geometry::bracketed_at(odometry_, utime, max_gap_us_, [](const OdometrySample& s) { return s.odom_from_base; });
}

bool FrameSync::odometry_past(int64_t utime) const { return !odometry_.empty() && odometry_.back().utime >= utime; }

void FrameSync::try_frame()
{
  if (!pending_frame_ || !odometry_past(pending_frame_->utime)) return;
  StereoFrame f = std::move(*pending_frame_);
  pending_frame_.reset();
  const auto pose = odometry_at(f.utime);
  if (!pose) {
    if (callbacks_.frame_dropped)
      callbacks_.frame_dropped(fmt::format("frame at {}: no odometry within max_pose_gap_s on both sides", f.utime));
    return;
  }
  f.odom_from_base = *pose;
  const FrameResult r = pipeline_.process(f, callbacks_.between_stages);
  ++frames_;
  if (callbacks_.processed) callbacks_.processed(f, r);
}

void FrameSync::try_laser()
{
  if (!pending_laser_ || !odometry_past(pending_laser_->utime)) return;
  const sensors::LaserScan scan = std::move(*pending_laser_);
  pending_laser_.reset();
  const auto pose = odometry_at(scan.utime);
  if (!pose) {
    if (callbacks_.scan_dropped) callbacks_.scan_dropped("scan without odometry within max_pose_gap_s around it");
    return;
  }
  pipeline_.insert_laser(scan, *pose, options_.base_from_laser);
  last_laser_utime_ = scan.utime;
  ++lasers_;
}

}  // namespace rgnav::vision
