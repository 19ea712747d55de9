// A generated building on disk, in the IPA building maps' conventions (sim/image_world.h reads
// them): <stem>.png, <stem>_furnitures.png, <stem>_gt_segmentation.png, and <stem>.json with the
// rooms, doorways and room graph in the world frame the simulator gives the image (origin at
// the lower-left corner, x right, y up, metres).
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "building_layout.h"
#include "building_raster.h"

namespace rgnav::buildings {

// The stem of seed's files: rand_<seed>.
std::string building_stem(uint64_t seed);

// Rooms (kind, rectangles, the name sim::rooms_from_segmentation gives it), doorways (end
// points, width, the rooms they join) and the room graph's edges.
nlohmann::json building_json(const Building& building, const BuildingImages& images);

// How many buildings the map paths show: a building's plain and furnished maps
// (<stem>.png, <stem>_furnitures.png) count once.
size_t count_buildings(const std::vector<std::string>& map_paths);

// Writes the four files into dir (created); throws std::runtime_error naming a file it cannot write.
void write_building(const Building& building, const BuildingImages& images, const std::string& dir);

}  // namespace rgnav::buildings
