#include "door_vision.h"

#include <opencv2/imgproc.hpp>

#include "drivers/stereo/stereo_calibration.h"
#include "sim/stereo_renderer.h"
#include "vision/dense_stereo.h"
#include "vision/object_rectangles.h"
#include "vision/rectangle_detector.h"

namespace rgnav::gateway_detector::tools {

DoorVision make_door_vision(const sim::World& world, const std::string& calibration_file, double rate_hz, uint64_t seed)
{
  const stereo::StereoCalibration cal = stereo::load_stereo_calibration(calibration_file);
  sim::StereoRenderOptions ro;
  ro.noise_seed = seed;
  auto renderer = std::make_shared<sim::StereoRenderer>(world, cal, ro);
  vision::DisparityOptions dopt;
  dopt.num_disparities = 96;
  auto stereo = std::make_shared<vision::DenseStereo>(dopt);
  const vision::Pinhole cam{cal.M1(0, 0), cal.M1(1, 1), cal.M1(0, 2), cal.M1(1, 2)};
  vision::RectangleDetectorOptions o;
  o.refine.focal_baseline = cal.M1(0, 0) * cal.baseline();
  const Eigen::Isometry3d base_from_camera = stereo::base_from_left_camera(cal, 0.0, 0.0);
  DoorVision v;
  v.rate_hz = rate_hz;
  v.see = [renderer, stereo, cam, o, base_from_camera](const sim::Pose2& truth, const std::vector<uint8_t>& doors_open,
                                                       int64_t frame) {
    sim::HeadView view;
    view.robot = truth;
    view.door_open = doors_open;
    view.frame = static_cast<uint64_t>(frame);
    const sim::StereoRender r = renderer->render(view);
    cv::Mat left, right;
    cv::cvtColor(r.left.image, left, cv::COLOR_BGR2GRAY);
    cv::cvtColor(r.right.image, right, cv::COLOR_BGR2GRAY);
    std::vector<Rectangle3> out;
    for (const auto& d : vision::detect_rectangles(left, stereo->disparity(left, right), 1, cam, o)) {
      const vision::ObjectRectangle b = vision::to_object(d.camera, base_from_camera);
      Rectangle3 g;
      for (int i = 0; i < 4; ++i) g.corners[i] = b.corners[i];
      g.normal = b.normal;
      g.width = b.width;
      g.height = b.height;
      out.push_back(g);
    }
    return out;
  };
  return v;
}

}  // namespace rgnav::gateway_detector::tools
