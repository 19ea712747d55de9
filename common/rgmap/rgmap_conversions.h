// RG map <-> LCM messages (RG_MAP, RG_REGION, RG_GRAPH). Round-trip tested.
#pragma once

#include "rgmap/rg_graph.h"
#include "rgmap/rg_map.h"
#include "rgnav/rg_graph_t.hpp"
#include "rgnav/rg_map_t.hpp"

namespace rgnav::rgmap {

region_t to_msg(const Region& r);
gateway_t to_msg(const Gateway& g);
rg_map_t to_msg(const RgMap& m);
rg_graph_t to_msg(const RgGraph& g, int64_t utime);

// Throws std::invalid_argument on content the model refuses (duplicate ids, bad bitmap).
Rectangle3d from_msg(const rectangle3d_t& m);
Region from_msg(const region_t& m);
Gateway from_msg(const gateway_t& m);
RgMap from_msg(const rg_map_t& m);

}  // namespace rgnav::rgmap
