#include "rendered_wall_objects.h"

#include "percentile.h"
#include "rendered_view_rig.h"

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "drivers/stereo/stereo_calibration.h"
#include "sim/stereo_renderer.h"
#include "sim/world_yaml.h"
#include "vision/dense_stereo.h"
#include "vision/object_rectangles.h"
#include "vision/rectangle_detector.h"

namespace rgnav::bench {
namespace {


Corners wall_object_corners(const sim::WallObject& o)
{
  return {Eigen::Vector3d(o.a.x(), o.a.y(), o.z_min), Eigen::Vector3d(o.b.x(), o.b.y(), o.z_min),
          Eigen::Vector3d(o.b.x(), o.b.y(), o.z_max), Eigen::Vector3d(o.a.x(), o.a.y(), o.z_max)};
}

// The direction a wall object faces: away from the wall nearest to its middle.
Eigen::Vector2d facing(const sim::World& world, const sim::WallObject& o)
{
  const Eigen::Vector2d centre = 0.5 * (o.a + o.b), along = (o.b - o.a).normalized();
  Eigen::Vector2d normal(-along.y(), along.x());
  double nearest = 1e9;
  Eigen::Vector2d off = normal;
  for (const auto& w : world.walls) {
    const Eigen::Vector2d ab = w.b - w.a;
    const double t = ab.squaredNorm() > 0 ? std::clamp((centre - w.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
    const Eigen::Vector2d d = centre - (w.a + t * ab);
    if (d.norm() < nearest) {
      nearest = d.norm();
      off = d;
    }
  }
  return off.dot(normal) >= 0 ? normal : Eigen::Vector2d(-normal);
}

struct KindTally
{
  int views = 0, found = 0, called_whiteboard = 0;
  std::vector<double> corner_err, height_err, width_err;
  nlohmann::json json() const
  {
    return {{"views", views},
            {"found", found},
            {"found_ratio", views ? static_cast<double>(found) / views : 0.0},
            {"called_whiteboard", called_whiteboard},
            {"called_whiteboard_ratio_of_found", found ? static_cast<double>(called_whiteboard) / found : 0.0},
            {"corner_error_max_m_p50", percentile(corner_err, 0.5)},
            {"height_error_m_p50", percentile(height_err, 0.5)},
            {"width_error_m_p50", percentile(width_err, 0.5)}};
  }
};

}  // namespace

nlohmann::json rendered_wall_objects(const std::string& world_file, const std::string& calibration_file, int views, uint64_t seed)
{
  const RenderedViewRig rig(world_file, calibration_file, seed);

  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  KindTally boards, posters;
  int drawn = 0, attempts = 0;
  nlohmann::json j;
  if (rig.world.wall_objects.empty()) return j;
  while (drawn < views && attempts < 50 * views) {
    ++attempts;
    const sim::WallObject& obj =
        rig.world.wall_objects[static_cast<size_t>(uni(rng) * static_cast<double>(rig.world.wall_objects.size())) % rig.world.wall_objects.size()];
    const Eigen::Vector2d along = (obj.b - obj.a).normalized();
    const Eigen::Vector2d centre = 0.5 * (obj.a + obj.b);
    const double dist = 1.2 + 2.8 * uni(rng), off = (uni(rng) * 2 - 1) * 50.0 * M_PI / 180.0;
    // From the side it hangs on: it stands off its wall (the nearest one) toward the room.
    const Eigen::Vector2d normal = facing(rig.world, obj);
    const Eigen::Vector2d at = centre + dist * (std::cos(off) * normal + std::sin(off) * along);
    sim::HeadView view;
    view.robot = sim::Pose2{at.x(), at.y(), std::atan2(centre.y() - at.y(), centre.x() - at.x())};
    view.tilt = std::atan2(0.5 * (obj.z_min + obj.z_max) - rig.camera_height, dist);
    view.frame = static_cast<uint64_t>(attempts);
    const Eigen::Isometry3d world_from_cam = rig.renderer.world_from_left_camera(view);
    const Eigen::Isometry3d cam_from_world = world_from_cam.inverse();
    const Corners truth = wall_object_corners(obj);
    // Every corner in view and the object the nearest thing there (not hidden, not behind its wall).
    const sim::CameraRender probe = rig.renderer.render_camera(world_from_cam, rig.cal.M1);
    bool visible = true;
    for (const auto& c : truth) {
      const auto px = pixel_in_view(rig.cam, probe.depth, cam_from_world * c);
      if (!px) {
        visible = false;
        break;
      }
      if (std::fabs(probe.depth.at<float>(px->v, px->u) - px->depth) > 0.1) visible = false;
    }
    if (!visible) continue;
    ++drawn;
    const bool board = obj.kind == sim::WallObject::Kind::kWhiteboard;
    KindTally& tally = board ? boards : posters;
    ++tally.views;
    const sim::StereoRender r = rig.renderer.render(view);
    cv::Mat left, right;
    cv::cvtColor(r.left.image, left, cv::COLOR_BGR2GRAY);
    cv::cvtColor(r.right.image, right, cv::COLOR_BGR2GRAY);
    const auto detected = vision::detect_rectangles(left, rig.stereo.disparity(left, right), 1, rig.cam, rig.detector);
    double best = 1e9;
    const vision::DetectedRectangle* match = nullptr;
    for (const auto& d : detected) {
      Corners w;
      for (int i = 0; i < 4; ++i) w[i] = world_from_cam * d.camera.corners[i];
      const double e = max_corner_distance(w, truth);
      if (e < best) {
        best = e;
        match = &d;
      }
    }
    if (!match || best >= 0.10) continue;
    ++tally.found;
    tally.corner_err.push_back(best);
    // The rig.world frame is a base frame on the floor: the kind as the vision gives it.
    const vision::ObjectRectangle as_object = vision::to_object(match->camera, world_from_cam, {}, match->grey_inside);
    if (as_object.kind == 2) ++tally.called_whiteboard;   // rectangle3d_t::KIND_WHITEBOARD
    tally.height_err.push_back(std::fabs(as_object.height - (obj.z_max - obj.z_min)));
    tally.width_err.push_back(std::fabs(as_object.width - (obj.b - obj.a).norm()));
  }
  j["views"] = drawn;
  j["whiteboards"] = boards.json();
  j["posters"] = posters.json();
  return j;
}

}  // namespace rgnav::bench
