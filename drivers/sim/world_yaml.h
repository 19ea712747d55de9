// Reads and writes rgnav world files (format: config/worlds/README.md). Reading goes through
// config::Config, so a malformed file is refused with a ConfigError naming the file and the
// key ("worlds/x.yaml: key 'doors[2].hinge': expected 2 numbers, got 3"), and unknown keys
// are errors too.
#pragma once

#include <string>

#include "config/config.h"
#include "sim/world.h"

namespace rgnav::sim {

// Any world file: an rgnav world (.yaml with walls/regions/...), a ROS map_server map
// (.yaml with `image:` and `resolution:`), or a bare occupancy image (.png/.pgm, IPA
// conventions; a sibling <stem>_gt_segmentation.png supplies the room labels).
World load_world(const std::string& path);

// An rgnav world from YAML text; base_dir resolves relative image paths.
World parse_world_yaml(const config::Config& cfg, const std::string& base_dir);

// Writes the world as rgnav YAML (deterministic formatting: the same World gives the same
// bytes). Image-derived walls are written out as walls.
std::string world_to_yaml(const World& world);

// Resolves a world argument: an existing path, else <worlds_dir>/<name>.yaml.
std::string resolve_world_path(const std::string& name_or_path, const std::string& worlds_dir);

}  // namespace rgnav::sim
