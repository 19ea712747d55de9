#include "rendered_doors.h"

#include "percentile.h"
#include "rendered_view_rig.h"

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

#include "drivers/stereo/stereo_calibration.h"
#include "sim/stereo_renderer.h"
#include "sim/world_yaml.h"
#include "vision/dense_stereo.h"
#include "vision/rectangle_detector.h"

namespace rgnav::bench {
namespace {

constexpr double kFrameWidth = 0.06;  // the renderer's jambs and lintel (render_faces.cpp) ...
constexpr double kFrameDepth = 0.2;   // ... across the wall: their faces stand half this in front of it

// The frame's face toward `viewer`: its opening (widen 0, top the door's height) or its outer
// outline (widen and top by the frame's width).
Corners door_outline(const sim::Door& d, double widen, double top, const Eigen::Vector2d& viewer)
{
  const Eigen::Vector2d along = (d.latch - d.hinge).normalized();
  Eigen::Vector2d normal(-along.y(), along.x());
  if (normal.dot(viewer - d.hinge) < 0) normal = -normal;
  const Eigen::Vector2d face = 0.5 * kFrameDepth * normal;
  const Eigen::Vector2d h = d.hinge - widen * along + face, l = d.latch + widen * along + face;
  return {Eigen::Vector3d(h.x(), h.y(), 0.0), Eigen::Vector3d(l.x(), l.y(), 0.0), Eigen::Vector3d(l.x(), l.y(), top),
          Eigen::Vector3d(h.x(), h.y(), top)};
}

}  // namespace

nlohmann::json rendered_doors(const std::string& world_file, const std::string& calibration_file, int views, uint64_t seed)
{
  const RenderedViewRig rig(world_file, calibration_file, seed);

  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  int drawn = 0, attempts = 0, found = 0, rectangles = 0;
  std::vector<double> corner_err, height_err, width_err, frame_ms;
  nlohmann::json j;
  if (rig.world.doors.empty()) return j;
  while (drawn < views && attempts < 50 * views) {
    ++attempts;
    const sim::Door& door = rig.world.doors[static_cast<size_t>(uni(rng) * static_cast<double>(rig.world.doors.size())) % rig.world.doors.size()];
    const Eigen::Vector2d along = (door.latch - door.hinge).normalized(), normal(-along.y(), along.x());
    const Eigen::Vector2d centre = 0.5 * (door.hinge + door.latch);
    const double dist = 2.4 + 2.6 * uni(rng), off = (uni(rng) * 2 - 1) * 50.0 * M_PI / 180.0;
    const double side = uni(rng) < 0.5 ? 1.0 : -1.0;
    const Eigen::Vector2d at = centre + dist * side * (std::cos(off) * normal + std::sin(off) * along);
    sim::HeadView view;
    view.robot = sim::Pose2{at.x(), at.y(), std::atan2(centre.y() - at.y(), centre.x() - at.x())};
    view.tilt = std::atan2(0.5 * door.height - rig.camera_height, dist);
    view.frame = static_cast<uint64_t>(attempts);
    const Eigen::Isometry3d world_from_cam = rig.renderer.world_from_left_camera(view);
    const Eigen::Isometry3d cam_from_world = world_from_cam.inverse();
    // Every corner of the frame's outline in view and not hidden (the depth drawn there is the
    // frame's, within its depth across the wall).
    const sim::CameraRender probe = rig.renderer.render_camera(world_from_cam, rig.cal.M1);
    bool visible = true;
    for (const auto& c : door_outline(door, kFrameWidth, door.height + kFrameWidth, at)) {
      const auto px = pixel_in_view(rig.cam, probe.depth, cam_from_world * c);
      if (!px) {
        visible = false;
        break;
      }
      float nearest = 1e9f;
      for (int dv = -3; dv <= 3; ++dv)
        for (int du = -3; du <= 3; ++du) {
          const float z = probe.depth.at<float>(px->v + dv, px->u + du);
          if (z > 0.0f) nearest = std::min(nearest, z);
        }
      if (std::fabs(nearest - px->depth) > 0.25) visible = false;
    }
    if (!visible) continue;
    ++drawn;
    const sim::StereoRender r = rig.renderer.render(view);
    const auto t0 = std::chrono::steady_clock::now();
    cv::Mat left, right;
    cv::cvtColor(r.left.image, left, cv::COLOR_BGR2GRAY);
    cv::cvtColor(r.right.image, right, cv::COLOR_BGR2GRAY);
    const auto detected = vision::detect_rectangles(left, rig.stereo.disparity(left, right), 1, rig.cam, rig.detector);
    frame_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    rectangles += static_cast<int>(detected.size());
    const Corners opening = door_outline(door, 0.0, door.height, at), outer = door_outline(door, kFrameWidth, door.height + kFrameWidth, at);
    double best = 1e9;
    bool match_outer = false;
    const vision::DetectedRectangle* match = nullptr;
    for (const auto& d : detected) {
      Corners w;
      for (int i = 0; i < 4; ++i) w[i] = world_from_cam * d.camera.corners[i];
      const double e_open = max_corner_distance(w, opening), e_outer = max_corner_distance(w, outer);
      if (std::min(e_open, e_outer) < best) {
        best = std::min(e_open, e_outer);
        match_outer = e_outer < e_open;
        match = &d;
      }
    }
    if (!match || best >= 0.10) continue;
    ++found;
    corner_err.push_back(best);
    // The side nearer the vertical is the height.
    const Eigen::Vector3d a = world_from_cam.linear() * (match->camera.corners[1] - match->camera.corners[0]);
    const bool a_vertical = std::fabs(a.normalized().z()) > 0.7;
    const double h = a_vertical ? match->camera.side_a : match->camera.side_b, w = a_vertical ? match->camera.side_b : match->camera.side_a;
    height_err.push_back(std::fabs(h - (door.height + (match_outer ? kFrameWidth : 0.0))));
    width_err.push_back(std::fabs(w - (door.width() + (match_outer ? 2 * kFrameWidth : 0.0))));
  }
  j["views"] = drawn;
  j["found"] = found;
  j["found_ratio"] = drawn ? static_cast<double>(found) / drawn : 0.0;
  j["rectangles_per_view"] = drawn ? static_cast<double>(rectangles) / drawn : 0.0;
  j["corner_error_max_m_p50"] = percentile(corner_err, 0.5);
  j["corner_error_max_m_p95"] = percentile(corner_err, 0.95);
  j["height_error_m_p50"] = percentile(height_err, 0.5);
  j["width_error_m_p50"] = percentile(width_err, 0.5);
  j["detect_ms_p50"] = percentile(frame_ms, 0.5);
  return j;
}

}  // namespace rgnav::bench
