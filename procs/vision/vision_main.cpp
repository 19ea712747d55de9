// vision: dense stereo into an OctoMap around the robot, fused with the laser, projected to the
// OBSTACLES_3D grid. STEREO_IMAGES + ODOMETRY + LASER_FRONT -> OBSTACLES_3D.
//   vision [--config config/vision.yaml]
#include <opencv2/core.hpp>

#include "drivers/stereo/stereo_calibration.h"
#include "runtime/process_main.h"
#include "vision/rig_from_calibration.h"
#include "vision/vision_node.h"
#include "vision/vision_options.h"

namespace vis = rgnav::vision;

int main(int argc, char** argv)
{
  return rgnav::runtime::process_main(argc, argv, "vision", [](rgnav::runtime::ProcessContext& ctx) {
    const auto options = vis::load_vision_options(ctx.config, ctx.robot, ctx.config_path);
    cv::setNumThreads(options.opencv_threads);
    const auto rig = vis::rig_from_calibration(rgnav::stereo::load_stereo_calibration(options.calibration_file));
    return std::make_shared<vis::VisionNode>(ctx.node, options, rig);
  });
}
