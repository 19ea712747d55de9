#include "sim/sim_stereo_feed.h"

#include <spdlog/spdlog.h>

#include "drivers/stereo/stereo_calibration.h"
#include "rgnav/odometry_t.hpp"
#include "sim/world_yaml.h"

namespace rgnav::sim {

SimStereoFeed::SimStereoFeed(runtime::Node& node, const stereo::CaptureOptions& options, double robot_radius)
{
  SimStereoSourceOptions o;
  o.pan = options.pan;
  o.tilt = options.tilt;
  o.render.noise_sigma = options.sim.noise_sigma;
  o.render.noise_seed = static_cast<uint64_t>(options.sim.noise_seed);
  o.people_seed = static_cast<uint64_t>(options.sim.people_seed);
  o.robot_radius = robot_radius;
  o.grayscale = options.folder.grayscale;  // capture.grayscale, for every source
  owned_ = std::make_unique<SimStereoSource>(load_world(options.sim.world_file),
                                             stereo::load_stereo_calibration(options.sim.calibration_file), o);
  source_ = owned_.get();
  node.subscribe<odometry_t>(options.sim.truth_channel, [this](const odometry_t& m) {
    ++received_;
    const Pose2 pose{m.odom_from_base.x, m.odom_from_base.y, m.odom_from_base.theta};
    if (!source_->on_truth(m.utime, pose)) {
      if (++dropped_ == 1 || dropped_ % 100 == 0)
        spdlog::warn("SIM_TRUTH dropped ({} so far): non-finite pose or not newer than the last", dropped_);
    }
  });
}

std::unique_ptr<stereo::StereoSource> SimStereoFeed::take_source() { return std::move(owned_); }

}  // namespace rgnav::sim
