// What the rendered-view evaluations share (rendered_doors.h, rendered_wall_objects.h): how far a
// detected rectangle lies from the true one, and the camera rig they look through — the world
// rendered by the simulated head with its calibration, dense stereo as the vision bench runs it,
// the pinhole of the left camera and the rectangle detector's options for that rig.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "drivers/stereo/stereo_calibration.h"
#include "sim/stereo_renderer.h"
#include "sim/world_yaml.h"
#include "vision/dense_stereo.h"
#include "vision/rectangle_detector.h"

namespace rgnav::bench {

// A rectangle's corners in the world frame.
using Corners = std::array<Eigen::Vector3d, 4>;

// Largest corner distance under the best pairing of the corners around (either way, any start).
inline double max_corner_distance(const Corners& a, const Corners& b)
{
  double best = 1e9;
  for (int dir : {1, -1})
    for (int shift = 0; shift < 4; ++shift) {
      double worst = 0.0;
      for (int i = 0; i < 4; ++i) worst = std::max(worst, (a[i] - b[((shift + dir * i) % 4 + 4) % 4]).norm());
      best = std::min(best, worst);
    }
  return best;
}

// Where a world point falls in a rendered camera view (pixel and depth), if in front of the camera
// by at least 0.3 m and at least 3 pixels inside the image (room for a 7 x 7 window about it).
struct PixelInView
{
  int u = 0, v = 0;
  double depth = 0;   // [m] along the optical axis
};
template <class Pinhole>
std::optional<PixelInView> pixel_in_view(const Pinhole& cam, const cv::Mat& depth_image, const Eigen::Vector3d& in_camera)
{
  const Eigen::Vector2d px = cam.project(in_camera);
  const int u = static_cast<int>(px.x()), v = static_cast<int>(px.y());
  if (in_camera.z() < 0.3 || u < 3 || v < 3 || u >= depth_image.cols - 3 || v >= depth_image.rows - 3) return std::nullopt;
  return PixelInView{u, v, in_camera.z()};
}

struct RenderedViewRig
{
  RenderedViewRig(const std::string& world_file, const std::string& calibration_file, uint64_t seed)
      : world(sim::load_world(world_file)),
        cal(stereo::load_stereo_calibration(calibration_file)),
        renderer(world, cal, render_options(seed)),
        stereo(disparity_options()),
        cam{cal.M1(0, 0), cal.M1(1, 1), cal.M1(0, 2), cal.M1(1, 2)},
        camera_height(stereo::base_from_left_camera(cal, 0.0, 0.0).translation().z())
  {
    detector.refine.focal_baseline = cal.M1(0, 0) * cal.baseline();
  }

  const sim::World world;
  const stereo::StereoCalibration cal;
  const sim::StereoRenderer renderer;
  const vision::DenseStereo stereo;
  const vision::Pinhole cam;
  vision::RectangleDetectorOptions detector;
  const double camera_height;   // [m] the left camera's centre over the floor, head level

 private:
  static sim::StereoRenderOptions render_options(uint64_t seed)
  {
    sim::StereoRenderOptions ro;
    ro.noise_seed = seed;
    return ro;
  }
  static vision::DisparityOptions disparity_options()
  {
    vision::DisparityOptions d;
    d.num_disparities = 96;
    return d;
  }
};

}  // namespace rgnav::bench
