// Random buildings for the benchmarks (issue 33): a floor plan drawn from a seed, made of
// axis-aligned rectangles on the 0.05 m pixel grid of the IPA building maps. The plan is
// abstract (spaces, their rectangles, the doorways between them); building_raster.h draws it as
// the IPA image triple. Every rule of the RG kernel was fitted on a few named maps: these
// buildings exist so that failure counts come from many maps no rule was fitted to.
//
// A building is a hallway system (straight, L, T, crossing or a ring around a block of rooms,
// 1.2-3.5 m wide, its arms sometimes separate spaces joined by a doorway) with strips of rooms
// along it (small offices to open halls), rooms behind rooms reached only through them, rooms
// with a second door to a neighbour, doors 0.8-1.6 m and wide openings 2-3 m. Its size is
// bounded so that a tour through every room stays within a few hundred metres.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace rgnav::buildings {

// Pixel grid: x = column (right), y = row (down), half-open [x0, x1) x [y0, y1).
struct PixelRect
{
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  bool overlaps(const PixelRect& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

enum class SpaceKind { kHallway, kRoom, kHall };
const char* to_string(SpaceKind kind);

// One room of the ground truth: a union of rectangles that touch or overlap (hallway arms).
struct Space
{
  SpaceKind kind = SpaceKind::kRoom;
  std::vector<PixelRect> rects;
};

// A doorway in the wall between spaces a and b. The wall lies on the grid line `line`: between
// columns line-1 and line (vertical wall) or rows line-1 and line (horizontal wall); the opening
// spans [from, to) along it. The ground truth closes it across the wall's thickness.
struct Doorway
{
  int a = 0, b = 0;          // space indices
  bool vertical = false;     // the wall runs along y
  int line = 0;
  int from = 0, to = 0;
  bool wide = false;         // an opening of 2-3 m rather than a door
  int width_px() const { return to - from; }
};

struct Building
{
  uint64_t seed = 0;
  std::string layout;        // straight, L, T, cross, ring
  int width = 0, height = 0; // image size [px]
  std::vector<Space> spaces;
  std::vector<Doorway> doorways;
};

constexpr double kMetresPerPixel = 0.05;   // the IPA maps' resolution
inline int to_pixels(double metres) { return static_cast<int>(std::lround(metres / kMetresPerPixel)); }

// The building of `seed` (the same seed gives the same building on every platform: sim::Rng).
Building generate_building(uint64_t seed);

// Wall thickness [px] between spaces a and b (b = -1: the outside), 1-4 px as in scanned maps,
// outer walls 2-4 px; drawn from the seed and the pair, so each wall keeps one thickness.
int wall_thickness_px(const Building& building, int a, int b);

// Space indices adjacent through doorways (the room graph), one list per space.
std::vector<std::vector<int>> doorway_graph(const Building& building);

// Per space: 1 if doorways lead to it from space 0 (the first hallway).
std::vector<char> reachable_through_doorways(const Building& building);

}  // namespace rgnav::buildings
