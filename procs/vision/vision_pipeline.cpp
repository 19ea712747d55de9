#include "vision/vision_pipeline.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace rgnav::vision {

namespace {

using Clock = std::chrono::steady_clock;
double ms_between(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }

StereoRig checked(const StereoRig& rig)
{
  if (const std::string why = check_rig(rig); !why.empty()) throw std::invalid_argument("stereo rig: " + why);
  return rig;
}

}  // namespace

VisionPipeline::VisionPipeline(const StereoRig& rig, const VisionOptions& options)
    : rig_(checked(rig)),
      options_(options),
      rectifier_(rig_, options.rectify_alpha),
      stereo_(options.disparity),
      matching_camera_(rectifier_.camera().scaled_down(options.disparity.downscale)),
      map_(options.map)
{
}

FrameResult VisionPipeline::process(const StereoFrame& frame, const std::function<void()>& between_stages)
{
  const auto stage_done = [&] {
    if (between_stages) between_stages();
  };
  FrameResult r;
  const auto t0 = Clock::now();
  cv::Mat left, right;
  rectifier_.rectify(frame.left, frame.right, &left, &right);
  const auto t1 = Clock::now();
  const cv::Mat disparity = stereo_.disparity(left, right);
  const auto t2 = Clock::now();
  stage_done();

  std::vector<Eigen::Vector3f> points = disparity_to_points(disparity, matching_camera_, options_.points);
  const Eigen::Isometry3d base_from_camera = vision::base_from_camera(rig_, frame.pan, frame.tilt);
  Eigen::Isometry3d base_from_rectified = base_from_camera;
  base_from_rectified.linear() = base_from_camera.linear() * rectifier_.camera().camera_from_rectified;
  const Eigen::Matrix3f rot = base_from_rectified.linear().cast<float>();
  const Eigen::Vector3f trans = base_from_rectified.translation().cast<float>();
  for (Eigen::Vector3f& p : points) p = rot * p + trans;
  r.points = points.size();
  const auto t3 = Clock::now();

  // What this frame's camera could see: where a cell that no point hits is seen to be empty.
  const double focal_baseline = matching_camera_.focal * matching_camera_.baseline;
  StereoView view;
  view.base_from_camera = base_from_rectified;
  view.focal = matching_camera_.focal;
  view.cx = matching_camera_.cx;
  view.cy = matching_camera_.cy;
  view.width = matching_camera_.size.width;
  view.height = matching_camera_.size.height;
  // Nearer than the largest disparity searched, nothing is matched.
  view.min_depth = std::max(options_.points.min_depth,
                            focal_baseline / std::max(1, options_.disparity.min_disparity + options_.disparity.num_disparities));
  view.max_depth = std::min(options_.points.max_depth, options_.map.max_range);
  r.insert = map_.insert_stereo(points, base_from_camera.translation(), frame.odom_from_base, focal_baseline, frame.utime, &view);
  const auto t4 = Clock::now();
  stage_done();
  r.grid = map_.project(frame.odom_from_base, frame.utime);
  const auto t5 = Clock::now();
  if (options_.rectangles.enabled && frames_++ % options_.rectangles.every_frames == 0) {
    r.rectangles_run = true;
    cv::Mat grey = left;
    if (grey.channels() == 3) cv::cvtColor(left, grey, cv::COLOR_BGR2GRAY);
    const RectifiedCamera& full = rectifier_.camera();
    RectangleDetectorOptions o = options_.rectangles.detector;
    o.refine.focal_baseline = full.focal * full.baseline;
    const Pinhole pinhole{full.focal, full.focal, full.cx, full.cy};
    for (const auto& d : detect_rectangles(grey, disparity, options_.disparity.downscale, pinhole, o))
      r.rectangles.push_back(to_object(d.camera, base_from_rectified, options_.rectangles.kinds, d.grey_inside));
  }
  const auto t6 = Clock::now();
  r.rectify_ms = ms_between(t0, t1);
  r.disparity_ms = ms_between(t1, t2);
  r.points_ms = ms_between(t2, t3);
  r.map_ms = ms_between(t3, t4);
  r.project_ms = ms_between(t4, t5);
  r.rectangles_ms = ms_between(t5, t6);
  r.total_ms = ms_between(t0, t6);
  return r;
}

}  // namespace rgnav::vision
