// The vision's rectangles as objects of the robot's world (OBJECTS_3D, rectangle3d_t): from the
// rectified left camera's frame into the base frame at capture, with the side nearer the
// vertical as the height, the normal toward the robot, and a kind from size and orientation: an
// upright rectangle of a door's size reaching down to the floor is a door (diss. 4.2.2 takes
// such rectangles as door frames), a level one at table height a table top; an upright one
// hanging above the floor whose inside is white a whiteboard (of Table 3.1's 0.3 m up to a wall's
// 2.5 m: its outline alone is that of any picture, what is on it tells), a landscape one of a
// screen's size standing at desk height and not white a monitor; the rest unknown.
#pragma once

#include <Eigen/Geometry>

#include <array>
#include <cstdint>

#include "vision/rectangle3d.h"

namespace rgnav::vision {

struct ObjectRectangle
{
  std::array<Eigen::Vector3d, 4> corners;  // base frame, counter-clockwise seen from the front
  Eigen::Vector3d normal;                  // unit, toward the robot
  double width = 0.0;                      // [m] the side nearer the horizontal
  double height = 0.0;                     // [m] the side nearer the vertical
  int8_t kind = 0;                         // rectangle3d_t::KIND_*
};

struct KindOptions
{
  double door_min_width = 0.6, door_max_width = 1.4;    // [m]
  double door_min_height = 1.8, door_max_height = 2.5;  // [m]
  double door_max_bottom = 0.25;  // [m] a door frame reaches down to the floor
  double upright_max_normal_z = 0.2;
  double table_min_z = 0.45, table_max_z = 1.1;         // [m] a table top's height
  double level_min_normal_z = 0.9;
  double wall_min_bottom = 0.4;   // [m] whiteboards and monitors are above the floor
  double whiteboard_min_width = 0.25, whiteboard_max_width = 2.5;   // [m]
  double whiteboard_min_height = 0.18, whiteboard_max_height = 1.5; // [m]
  double whiteboard_min_grey = 170.0;  // mean grey level inside (0..255): white
  double monitor_min_width = 0.25, monitor_max_width = 0.8;    // [m] 12-32 inch screens
  double monitor_min_height = 0.18, monitor_max_height = 0.55; // [m]
  double monitor_max_bottom = 1.4;   // [m] on a desk (the bottom above table_min_z)
};

// grey_inside: the image's mean grey level inside the rectangle (DetectedRectangle::grey_inside;
// below 0: unknown, never a whiteboard).
ObjectRectangle to_object(const Rectangle3d& in_camera, const Eigen::Isometry3d& base_from_camera, const KindOptions& options = {},
                          double grey_inside = -1.0);

}  // namespace rgnav::vision
