// What the map knows around a place: how much of it is free and how much wall lies there. A goal
// that failed for good (ExplorerOptions::max_attempts) is tried again only once this changed
// near it — a person who stood in a doorway and walked on, a wall fragment the RG kernel dropped
// again, free space seen from another side — and not while nothing near it did, so exploring
// still ends when nothing reachable is left.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "explorer/explorer_options.h"
#include "rgmap/rg_map.h"

namespace rgnav::explorer {

struct PlaceView
{
  int free_samples = -1;           // lattice points free in some region's freespace (-1: never looked)
  double wall_m = 0;               // [m] length of the regions' line segments inside the neighbourhood

  bool known() const { return free_samples >= 0; }
};

// The map around `map_point` (map frame), over every region not merged away.
PlaceView view_of_place(const rgmap::RgMap& map, const Eigen::Vector2d& map_point, const PlaceViewOptions& o);

// Whether the map near the place changed between the two views (an unknown one: no).
bool place_changed(const PlaceView& then, const PlaceView& now, const PlaceViewOptions& o);

// State files: [free_samples, wall_m]; place_view_from_json throws std::invalid_argument on
// anything else.
nlohmann::json place_view_json(const PlaceView& v);
PlaceView place_view_from_json(const nlohmann::json& j);

}  // namespace rgnav::explorer
