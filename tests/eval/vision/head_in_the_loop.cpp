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
      resolution_(vision.vision.map.resolution),
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
  solids_ = world.boxes;
  for (const auto& t : world.tables)
    for (const auto& part : t.parts()) solids_.push_back(part);
}

void HeadInTheLoop::mark(const Pending& grid, const geometry::Pose2& world_from_odom)
{
  const double half_cell = 0.5 * resolution_;
  for (auto& [name, m] : marked_) m.cells_last = 0;
  for (const auto& b : solids_) {
    int cells = 0;
    for (const auto& q : grid.points) {
      const Eigen::Vector2d l = Eigen::Rotation2Dd(-b.yaw) * (world_from_odom * q - b.center);
      if (std::abs(l.x()) <= 0.5 * b.size.x() + half_cell && std::abs(l.y()) <= 0.5 * b.size.y() + half_cell) ++cells;
    }
    if (cells == 0) continue;
    Marked& m = marked_[b.name];
    ++m.grids;
    m.cells_last = cells;
    m.last_stamp = grid.stamp;
  }
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
  const auto& truth = sim.truth();
  const geometry::Pose2 world_from_base(truth.x, truth.y, truth.theta);
  for (const auto& o : out.odometry)
    world_from_odom_ = world_from_base * geometry::Pose2(o.odom_from_base.x, o.odom_from_base.y, o.odom_from_base.theta).inverse();
  for (const auto& e : out.collisions) {
    ContactView c;
    c.with = e.with;
    c.t_s = sim.time_s();
    if (last_delivered_stamp_ >= 0) c.grid_age_s = static_cast<double>(now - last_delivered_stamp_) * 1e-6;
    if (auto it = marked_.find(e.with); it != marked_.end()) {
      c.cells_now = it->second.cells_last;
      c.grids_marking = it->second.grids;
      if (it->second.last_stamp >= 0) c.last_marked_age_s = static_cast<double>(now - it->second.last_stamp) * 1e-6;
    }
    contacts_.push_back(c);
  }
  while (!pending_.empty() && pending_.front().due_utime <= now) {
    mark(pending_.front(), world_from_odom_);
    last_delivered_stamp_ = pending_.front().stamp;
    ca.on_obstacle_points(time::from_utime(pending_.front().stamp), std::move(pending_.front().points));
    pending_.pop_front();
  }
}

}  // namespace rgnav::bench
