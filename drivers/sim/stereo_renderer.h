// The simulated stereo head: renders the world into the left and right images of a calibrated
// rig on the pan-tilt head (drivers/stereo/stereo_calibration.h) at the robot's true pose, with
// a z-buffer over the world's planar faces (render_faces.h), deterministic surface texture
// (surface_texture.h), seeded Gaussian image noise, and the ground-truth depth of every pixel.
//
// Pinhole projection through each camera's matrix; a calibration with distortion is applied by
// remapping the ideal image (pixels whose ideal ray falls outside the ideal image stay black).
// The rendering is exact for the geometry: a pixel shows the face its centre's ray hits first.
#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

#include "drivers/stereo/stereo_calibration.h"
#include "sim/lms2xx_model.h"
#include "sim/render_faces.h"
#include "sim/surface_texture.h"
#include "sim/world.h"

namespace rgnav::sim {

struct StereoRenderOptions
{
  double noise_sigma = 2.0;  // [grey levels] Gaussian noise per pixel and channel; 0: none
  uint64_t noise_seed = 1;   // with the frame number: the same noise for the same frame
  double near = 0.05;        // [m] nothing nearer the camera is drawn
};

// What changes between frames.
struct HeadView
{
  Pose2 robot;                     // true pose of the base in the world
  double pan = 0.0;                // [rad] CCW +
  double tilt = 0.0;               // [rad] + = looking up
  std::vector<uint8_t> door_open;  // per World::doors; missing entries: the door's `open` flag
  std::vector<Circle> people;      // per World::people (fewer: the rest are not drawn)
  uint64_t frame = 0;              // keys the image noise
};

struct CameraRender
{
  cv::Mat image;  // CV_8UC3 BGR
  cv::Mat depth;  // CV_32F [m] along the optical axis; 0 where nothing was hit
};

struct StereoRender
{
  CameraRender left;
  CameraRender right;
};

class StereoRenderer
{
 public:
  // Throws std::invalid_argument when the calibration has skewed or differently sized cameras
  // the renderer cannot draw (it checks nothing the calibration loader already checked).
  StereoRenderer(const World& world, stereo::StereoCalibration calibration, StereoRenderOptions options = {});

  StereoRender render(const HeadView& view) const;
  // The same into `out`, reusing its buffers where nothing else holds them (a frame rate's worth
  // of fresh 640x480 buffers costs more in page faults than the drawing). Not for concurrent use:
  // one renderer draws one pair at a time.
  void render(const HeadView& view, StereoRender* out) const;

  // One camera with matrix K at a pose in the world (optical frame), no noise and no
  // distortion, over the static faces plus `extra` (tests and tools).
  CameraRender render_camera(const Eigen::Isometry3d& world_from_camera, const cv::Matx33d& K,
                             const std::vector<Face>& extra = {}) const;

  Eigen::Isometry3d world_from_left_camera(const HeadView& view) const;
  const stereo::StereoCalibration& calibration() const { return calibration_; }
  const std::vector<Face>& faces() const { return static_faces_; }

 private:
  void draw(const std::vector<const std::vector<Face>*>& face_sets, const Eigen::Isometry3d& world_from_camera,
            const cv::Matx33d& K, CameraRender* out) const;
  void finish(CameraRender* r, const cv::Mat& map_x, const cv::Mat& map_y, uint64_t noise_key) const;

  const World world_;
  const stereo::StereoCalibration calibration_;
  const StereoRenderOptions options_;
  const std::vector<Face> static_faces_;
  const SurfaceTexture texture_;
  // Distorted pixel -> ideal pixel, per camera (empty: no distortion).
  cv::Mat left_map_x_, left_map_y_, right_map_x_, right_map_y_;
  cv::Mat noise_bank_;  // 1 x N CV_16S Gaussian noise [grey levels]
  mutable cv::Mat index_;  // scratch: the face drawn at each pixel (-1: none)
};

}  // namespace rgnav::sim
