// One region of the RG map as the page draws it, everything in the map frame: line map, objects,
// bounding outline and centre (for its name), and the freespace bitmap with its grid's frame.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include "rgmap/rg_map.h"

namespace rgnav::viewer {

nlohmann::json region_json(const rgmap::Region& r);

}  // namespace rgnav::viewer
