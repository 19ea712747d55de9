// Which spaces of a drawn building the simulated robot can enter: the tour planner
// (drivers/sim/tour_planner.h) drives where the clearance to anything exceeds the robot radius
// plus its margin, starting in the largest such area (sim/image_world.h's start).
#pragma once

#include <opencv2/core.hpp>

#include <vector>

namespace rgnav::buildings {

// B21r radius 0.26 m (config/robot.yaml) + the tour planner's margin 0.08 m, and half a pixel
// for the distance transform's pixel centres.
constexpr double kRobotClearanceM = 0.26 + 0.08 + 0.025;

// Space indices (labels - 1, labels CV_32S as BuildingImages::labels) none of whose pixels is in
// the largest connected area of `map` pixels (CV_8U, 255 free) with more than clearance_m to
// any non-free pixel.
std::vector<int> spaces_out_of_reach(const cv::Mat& map, const cv::Mat& labels, int spaces,
                                     double clearance_m = kRobotClearanceM);

}  // namespace rgnav::buildings
