// Rectangular 3D objects from one view (diss. 3.3): a quadrangle in a rectified image, the
// projection of a rectangle in space (a door frame, a whiteboard, a monitor), gives the plane
// normal of the rectangle from its vanishing line (3.3.2), and with the measured 3D position
// of one or more of its corners (stereo) all four corners by ray-plane intersection (3.3.3).
// Camera frame: x right, y down, z along the optical axis; pixels of the rectified image.
#pragma once

#include <Eigen/Core>

#include <array>
#include <optional>

namespace rgnav::vision {

// A rectified pinhole camera (no distortion left).
struct Pinhole
{
  double fx = 500.0, fy = 500.0;  // [px] focal lengths
  double cx = 320.0, cy = 240.0;  // [px] principal point
  Eigen::Vector3d ray(const Eigen::Vector2d& pixel) const  // through the pixel, z = 1
  {
    return {(pixel.x() - cx) / fx, (pixel.y() - cy) / fy, 1.0};
  }
  Eigen::Vector2d project(const Eigen::Vector3d& p) const { return {cx + fx * p.x() / p.z(), cy + fy * p.y() / p.z()}; }
};

// Four image corners in order around the quadrangle (either way round).
using Quadrangle = std::array<Eigen::Vector2d, 4>;

struct Rectangle3d
{
  std::array<Eigen::Vector3d, 4> corners;  // camera frame, in the order of the quadrangle's
  Eigen::Vector3d normal;                  // unit, toward the camera
  double side_a = 0.0;  // [m] mean length of edges 0-1 and 3-2
  double side_b = 0.0;  // [m] mean length of edges 1-2 and 0-3
};

// The internal angles of the quadrangle [rad], at each corner. Reconstruction from pixels is
// reliable only while all lie well away from 0 and pi (diss. 3.3.4.1: 26 to 154 degrees).
std::array<double, 4> internal_angles(const Quadrangle& q);

// The unit normal of the plane the quadrangle is the projection of a rectangle in, toward the
// camera: the vanishing points of the two pairs of opposite sides (eq. 3.1), the line through
// them (the vanishing line) and n = C^T l (eq. 3.2). Nothing for a quadrangle that is no
// projection of a rectangle in front of the camera (degenerate sides, plane through the camera).
std::optional<Eigen::Vector3d> plane_normal(const Quadrangle& q, const Pinhole& camera);

// The rectangle (diss. 3.3.3): each measured corner (camera frame; nothing where stereo has no
// depth) is projected onto its own ray, gives the plane's offset along `normal`, and the offsets
// are averaged (the "base point" average of the dissertation); every corner is then where its ray
// meets that plane. Nothing without a measured corner, or when a ray misses the plane in front.
std::optional<Rectangle3d> intersect_rays(const Quadrangle& q, const Pinhole& camera, const Eigen::Vector3d& normal,
                                          const std::array<std::optional<Eigen::Vector3d>, 4>& measured);

// Every corner where its ray meets the plane n·X = d (d < 0: in front, n toward the camera).
std::optional<Rectangle3d> intersect_plane(const Quadrangle& q, const Pinhole& camera, const Eigen::Vector3d& normal, double d);

// plane_normal then intersect_rays.
std::optional<Rectangle3d> reconstruct_rectangle(const Quadrangle& q, const Pinhole& camera,
                                                 const std::array<std::optional<Eigen::Vector3d>, 4>& measured);

// What the refinement knows of its measurements' errors.
struct RefineOptions
{
  double sigma_px = 0.5;            // [px] a corner's position in the image (line fits, whole pixels)
  double focal_baseline = 60.0;     // [px m] f * B of the stereo rig the depths come from ...
  double sigma_disparity = 0.25;    // [px] ... and its disparity noise: sigma_z = z^2 sigma_d / (f B)
  int max_iterations = 50;
};

// The rectangle most likely to have been seen (an improvement over the dissertation's method,
// measured in ./rgnav bench vision): a rectangle (centre, orientation, width, height) fitted by
// Levenberg-Marquardt to the four image corners (sigma_px) and the measured corners' depths
// (the stereo model's sigma_z), from `initial` (reconstruct_rectangle's). The vanishing line's
// normal comes from the sides' directions alone and is poor where the quadrangle has very sharp
// or very flat angles (diss. 3.3.4.1); the fit uses every measurement by its own accuracy.
// Nothing if the fit leaves the camera's front or fails to converge.
std::optional<Rectangle3d> refine_rectangle(const Quadrangle& q, const Pinhole& camera, const Rectangle3d& initial,
                                            const std::array<std::optional<Eigen::Vector3d>, 4>& measured,
                                            const RefineOptions& options = {});

}  // namespace rgnav::vision
