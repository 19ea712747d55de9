// The simulated stereo head as a stereo_capture source (drivers/stereo/stereo_source.h): renders
// the world at the robot's true pose as the simulator reports it (SIM_TRUTH, fed in through
// on_truth by the node adapter), so stereo_capture publishes STEREO_IMAGES from the simulation
// as it does from the cameras, and the simulator's real-time loop never renders.
//
// What the simulator does not publish is followed here: people walk the simulator's people
// model (the same world, seed and robot pose; it matches the simulator's own people closely,
// not to the bit: the robot pose comes at the SIM_TRUTH rate, not every physics step), and
// doors follow their schedules on the time since the first SIM_TRUTH seen (exact when
// stereo_capture starts with the simulator).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "drivers/stereo/stereo_source.h"
#include "sim/people.h"
#include "sim/scene.h"
#include "sim/stereo_renderer.h"

namespace rgnav::sim {

struct SimStereoSourceOptions
{
  double pan = 0.0;   // [rad] head angles the images are rendered at (stereo_capture's pan/tilt)
  double tilt = 0.0;
  StereoRenderOptions render;
  uint64_t people_seed = 1;   // the simulator's seed (sim.yaml sim.seed): the same people choices
  double robot_radius = 0.26; // [m] people make way for a disc this size at the true pose
  bool grayscale = false;     // hand out 8-bit grey images (as the cameras do with grayscale: true)
};

class SimStereoSource final : public stereo::StereoSource
{
 public:
  SimStereoSource(const World& world, stereo::StereoCalibration calibration, SimStereoSourceOptions options);

  // The true pose at message time `utime` (SIM_TRUTH). Older or repeated times are ignored
  // (returns false), as are non-finite poses.
  bool on_truth(int64_t utime, const Pose2& world_from_base);

  // A pair rendered at the newest true pose, stamped with its time; nothing before the first
  // SIM_TRUTH or when none came since the last pair (no frame twice).
  std::optional<stereo::StereoFrame> next() override;
  std::string error() const override { return error_; }
  std::string describe() const override;

  // The last rendering (ground-truth depth for benchmarks), and how many were made.
  const StereoRender& last() const { return last_; }
  int64_t rendered() const { return rendered_; }
  const StereoRenderer& renderer() const { return renderer_; }

 private:
  const World world_;
  const SimStereoSourceOptions options_;
  const StereoRenderer renderer_;
  const Scene scene_;  // static clearance for the people model
  People people_;
  std::optional<int64_t> first_utime_, last_utime_, rendered_utime_;
  Pose2 pose_;
  std::vector<uint8_t> door_open_;
  StereoRender last_;
  int64_t rendered_ = 0;
  std::string error_;
};

}  // namespace rgnav::sim
