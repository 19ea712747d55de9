// RG map <-> JSON (schema: common/rgmap/README.md). The file format of `rgmap.json`, the RG
// kernel's checkpoint payload and `./rgnav render`'s input.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "rgmap/rg_map.h"

namespace rgnav::rgmap {

constexpr int kJsonSchemaVersion = 1;

nlohmann::json to_json(const RgMap& map);
// Throws std::invalid_argument naming the JSON path of the first problem.
RgMap from_json(const nlohmann::json& j);

}  // namespace rgnav::rgmap
