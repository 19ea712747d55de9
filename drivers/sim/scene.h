// The static part of a world as vertical segments in a uniform grid, for the two queries the
// simulator asks thousands of times a second: "where does this ray first hit something at
// height z?" (the laser) and "how far is the nearest obstacle in this height band?" (collision).
// Rays walk the grid cell by cell (Amanatides & Woo DDA) and test only the segments listed in
// the cells they cross. Doors are segments whose presence depends on a per-door open flag.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "sim/world.h"

namespace rgnav::sim {

struct SceneSegment
{
  Vec2 a;
  Vec2 b;
  float z_min;
  float z_max;
  int32_t door;   // index into World::doors, or -1 for static geometry
  int32_t owner;  // index into Scene::owner_names() (what a collision reports)
};

// Which segments a query considers: those overlapping [z_low, z_high] and not an open door.
struct HeightBand
{
  double z_low;
  double z_high;
};

struct RayHit
{
  double range = std::numeric_limits<double>::infinity();  // inf = nothing within max_range
  int32_t owner = -1;
};

struct Clearance
{
  double distance = std::numeric_limits<double>::infinity();
  int32_t owner = -1;
};

class Scene
{
 public:
  // cell_size: grid pitch [m]; 0.5 m keeps a few segments per cell in building-scale worlds.
  explicit Scene(const World& world, double cell_size = 0.5);

  // door_open[i] tells whether World::doors[i] is open (size must equal the door count).
  RayHit cast(const Vec2& origin, const Vec2& unit_dir, double max_range, const HeightBand& band,
              const std::vector<uint8_t>& door_open) const;
  // Distance from p to the nearest active segment, searched up to `search_radius`
  // (farther obstacles report infinity).
  Clearance clearance(const Vec2& p, double search_radius, const HeightBand& band,
                      const std::vector<uint8_t>& door_open) const;

  const std::vector<SceneSegment>& segments() const { return segments_; }
  const std::vector<std::string>& owner_names() const { return owner_names_; }
  Vec2 min_corner() const { return origin_; }
  Vec2 max_corner() const { return origin_ + Vec2(nx_ * cell_, ny_ * cell_); }

 private:
  bool active(const SceneSegment& s, const HeightBand& band, const std::vector<uint8_t>& door_open) const
  {
    return s.z_min <= band.z_high && s.z_max >= band.z_low && (s.door < 0 || !door_open[static_cast<size_t>(s.door)]);
  }
  void add_segment(const Vec2& a, const Vec2& b, double z_min, double z_max, int32_t door, const std::string& owner);
  void build_grid();

  std::vector<SceneSegment> segments_;
  std::vector<std::string> owner_names_;
  double cell_;
  Vec2 origin_{0, 0};
  int nx_ = 1;
  int ny_ = 1;
  std::vector<uint32_t> cell_start_;  // CSR: segments of cell c are cell_items_[cell_start_[c] .. cell_start_[c+1])
  std::vector<uint32_t> cell_items_;
};

// Ray-segment intersection: distance along the ray (unit_dir) or infinity.
double ray_segment(const Vec2& o, const Vec2& d, const Vec2& a, const Vec2& b);
// Ray-circle intersection from outside: distance or infinity (inside the circle: 0).
double ray_circle(const Vec2& o, const Vec2& d, const Vec2& c, double r);

}  // namespace rgnav::sim
