// From narrow passages to doors (diss. 4.2.2): 3D rectangles of door size whose normal is
// nearly horizontal are door-frame candidates; their two vertical edges, projected into the
// laser plane, must match the passage's gateway points (in either order) to make it a door.
#pragma once

#include <Eigen/Core>

#include <array>
#include <optional>

#include "gateway_detector/scan.h"

namespace rgnav::gateway_detector {

struct Rectangle3
{
  std::array<Eigen::Vector3d, 4> corners;  // any planar frame with z up
  Eigen::Vector3d normal{1, 0, 0};
  double width = 0.0;   // [m]
  double height = 0.0;  // [m]
};

struct DoorConfirmationOptions
{
  double min_width = 0.7;         // [m] door-frame size tolerance interval
  double max_width = 1.3;
  double min_height = 1.8;
  double max_height = 2.5;
  double max_normal_z = 0.2;      // |n_z| of a vertical door plane
  double match_distance = 0.25;   // [m] projected edge to gateway point
  double memory_s = 60.0;         // [s] how long a seen door frame is kept
};

// The two vertical edges of a door-like rectangle, projected into the plane (same frame as the
// rectangle's x, y), or nullopt if it is not door-like.
std::optional<std::array<Vec2, 2>> door_edges(const Rectangle3& r, const DoorConfirmationOptions& o);
// Both gateway points match the two edges, one each.
bool edges_match(const std::array<Vec2, 2>& edges, const Vec2& a, const Vec2& b, double tolerance);

}  // namespace rgnav::gateway_detector
