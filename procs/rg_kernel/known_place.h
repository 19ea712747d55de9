// Evidence that a robot position lies in a region the kernel already knows (diss. 6.1.1: the
// circular hallway and the missed gateway). Lying in a finalised region's freespace bitmap is
// not enough: that bitmap also holds what the region's robot saw through open doors it never
// crossed, so a robot that has just gone through such a door would "recognise" the room it
// left. A position counts as in region q only if q's own robot stood nearby and saw it:
// some laser origin of q within `max_origin_distance` has a straight line to the position
// through q's free cells that crosses no gateway line of the map. Through a door the line
// crosses the door's gateway (once it is known) or a wall (not free); along a hallway the
// robot walked before it does neither.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "rgmap/rg_map.h"

namespace rgnav::rg_kernel {

class RegionBuilder;

struct KnownPlaceOptions
{
  double max_origin_distance = 1.5;   // [m] a robot position of the known region at most this far
  int max_lines_tried = 8;            // nearest origins whose line of sight is checked, at most
};

class KnownPlaces
{
 public:
  // The finalised regions of `map` except `except`, with their robot positions from
  // `builders` (region frame), and every non-neutralized gateway line in the map frame.
  // `crossed` (map frame, points as in a gateway) is a gateway the robot has just crossed as the
  // gateway detector saw it then; its lines end lines of sight too. A crossing matched to a known
  // one keeps the known outline, measured on another visit: with pose error between the visits
  // the robot, just past the side it left by, can lie inside that outline, where every region
  // whose robot went through the junction "saw" it (office, SLAM poses: the hallway beyond a
  // crossing taken for the one the crossing was first entered from).
  KnownPlaces(const rgmap::RgMap& map, const std::map<int64_t, RegionBuilder>& builders, int64_t except,
              KnownPlaceOptions options, const std::vector<Eigen::Vector2d>& crossed = {});

  // The known region that holds the map point (the lowest id if several), 0 if none.
  int64_t region_holding(const Eigen::Vector2d& map_point) const;

 private:
  struct Place
  {
    int64_t id = 0;
    const rgmap::Region* region = nullptr;
    std::vector<Eigen::Vector2d> origins;   // map frame
  };
  bool sees(const Place& q, const Eigen::Vector2d& from, const Eigen::Vector2d& to) const;

  KnownPlaceOptions options_;
  std::vector<Place> places_;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> gateway_lines_;   // map frame
};

}  // namespace rgnav::rg_kernel
