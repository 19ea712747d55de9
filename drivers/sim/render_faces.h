// The world as the cameras see it: every visible surface a flat rectangle (walls, door leaves,
// frames and the wall above doors, box and table sides, people as many-sided prisms, posters,
// whiteboards, floor and ceiling), each with a material and a surface id that key its texture.
// Static faces are built once per world; doors and people change and are added per frame.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "sim/lms2xx_model.h"
#include "sim/world.h"

namespace rgnav::sim {

enum class Material : uint8_t
{
  kWall, kFloor, kCeiling, kDoorLeaf, kDoorFrame, kBox, kTableTop, kTableLeg, kPerson, kPoster, kWhiteboard
};

// The rectangle origin + s * u + t * v, s in [0, width], t in [0, height] (u, v unit and
// orthogonal); s and t in metres are also its texture coordinates.
struct Face
{
  Eigen::Vector3d origin{0, 0, 0};
  Eigen::Vector3d u{1, 0, 0};
  Eigen::Vector3d v{0, 0, 1};
  double width = 1.0;   // [m]
  double height = 1.0;  // [m]
  Material material = Material::kWall;
  uint32_t surface = 0;  // texture key: distinct per surface of the world
  double s_offset = 0;   // [m] added to s for the texture (faces of one surface continue it)
};

// Height of the ceiling: the top of the highest wall (2.5 m when there are no walls).
double ceiling_height(const World& world);

// Walls, the wall above each door and its frame, boxes, tables, wall objects, floor and ceiling
// (over the world's extent plus a margin).
std::vector<Face> static_faces(const World& world);

// Door leaves as they are (door_open[i] for World::doors[i]: closed across the opening, open
// folded flat beside the wall on the hinge side) and people (discs from the floor to their
// height, in the order of World::people). Appended to `out`.
void append_dynamic_faces(const World& world, const std::vector<uint8_t>& door_open,
                          const std::vector<Circle>& people, std::vector<Face>* out);

// The six faces of an upright box (corners CCW, from z_min to z_max).
void append_box(const std::vector<Vec2>& corners, double z_min, double z_max, Material m, uint32_t surface,
                std::vector<Face>* out);

}  // namespace rgnav::sim
