// stereo_capture's simulated head on the bus: loads the world and the calibration, builds the
// SimStereoSource and feeds it the true pose from SIM_TRUTH (odometry_t, odom_from_base = the
// pose in the world frame). Messages with a non-finite pose or going back in time are dropped
// and counted.
#pragma once

#include <memory>

#include "drivers/stereo/stereo_capture_node.h"
#include "runtime/node.h"
#include "sim/sim_stereo_source.h"

namespace rgnav::sim {

class SimStereoFeed
{
 public:
  // Throws config::ConfigError (naming the file) for a bad world or calibration file.
  SimStereoFeed(runtime::Node& node, const stereo::CaptureOptions& options, double robot_radius);
  // The source for StereoCaptureNode; this feed keeps a pointer to it, so keep the feed alive
  // as long as the node that owns the source.
  std::unique_ptr<stereo::StereoSource> take_source();
  int64_t truth_received() const { return received_; }
  int64_t truth_dropped() const { return dropped_; }

 private:
  std::unique_ptr<SimStereoSource> owned_;
  SimStereoSource* source_ = nullptr;
  int64_t received_ = 0;
  int64_t dropped_ = 0;
};

}  // namespace rgnav::sim
