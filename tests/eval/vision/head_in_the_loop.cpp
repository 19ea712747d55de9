#include "head_in_the_loop.h"

#include <cmath>
#include <stdexcept>

#include "collision_avoidance/grid_obstacles.h"
#include "vision/rig_from_calibration.h"

namespace rgnav::bench {

namespace {

vision::FrameSyncOptions sync_options(const vision::VisionNodeOptions& o)
{
  return {o.max_pose_gap, o.laser_period, o.base_from_laser};
}

}  // namespace

HeadInTheLoop::HeadInTheLoop(const sim::World& world, const stereo::StereoCalibration& calibration,
                             const vision::VisionNodeOptions& vision, const HeadLoopOptions& options)
    : options_(options),
      renderer_(world, calibration, options.render),
      pipeline_(vision::rig_from_calibration(calibration), vision.vision)
{
  if (!(options_.rate_hz > 0)) throw std::invalid_argument("head rate must be positive");
  vision::FrameSyncCallbacks cb;
  cb.processed = [this](const vision::StereoFrame& f, const vision::FrameResult& r) {
    frame_ms_.push_back(r.total_ms);
    const vision::ObstacleGrid& g = r.grid;
    pending_.push_back({f.utime + static_cast<int64_t>(std::llround(options_.latency_s * 1e6)), g.utime,
                        collision_avoidance::grid_obstacle_points(g.odom_from_grid, g.resolution, g.width, g.height, g.cells,
                                                                  options_.grid_occupied_min)});
  };
  sync_ = std::make_unique<vision::FrameSync>(pipeline_, sync_options(vision), std::move(cb));
}

void HeadInTheLoop::after_step(const sim::Simulator& sim, const sim::StepOutput& out,
                               collision_avoidance::CollisionAvoidance& ca)
{
  // The process hears odometry and scans as they come, frames when stereo_capture grabs them.
  for (const auto& o : out.odometry)
    sync_->on_odometry(o.utime, o.seq, geometry::Pose2(o.odom_from_base.x, o.odom_from_base.y, o.odom_from_base.theta));
  for (const auto& s : out.scans) sync_->on_laser(s);
  const int64_t now = sim.now_utime();
  if (next_frame_utime_ == 0) next_frame_utime_ = now;
  if (now >= next_frame_utime_) {
    next_frame_utime_ += static_cast<int64_t>(std::llround(1e6 / options_.rate_hz));
    sim::HeadView view;
    view.robot = sim.truth();
    view.pan = options_.pan;
    view.tilt = options_.tilt;
    view.door_open = sim.doors_open();
    view.people = sim.people();
    view.frame = ++frame_no_;
    renderer_.render(view, &render_);
    // As stereo_capture sends the pair and the vision decodes it.
    const auto left = stereo::decode_image(stereo::encode_image(render_.left.image, now, options_.encoding, options_.jpeg_quality));
    const auto right = stereo::decode_image(stereo::encode_image(render_.right.image, now, options_.encoding, options_.jpeg_quality));
    if (!left || !right) throw std::runtime_error("a rendered image did not decode");
    vision::StereoFrame f;
    f.utime = now;
    f.left = *left;
    f.right = *right;
    f.pan = options_.pan;
    f.tilt = options_.tilt;
    sync_->on_frame(std::move(f));
  }
  while (!pending_.empty() && pending_.front().due_utime <= now) {
    ca.on_obstacle_points(time::from_utime(pending_.front().stamp), std::move(pending_.front().points));
    pending_.pop_front();
  }
}

}  // namespace rgnav::bench
