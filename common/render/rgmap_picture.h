// Pictures and exports of an RG map: regions coloured (freespace), line maps, gateways with
// their class, crossing points, the RG graph and objects — the kind of figure the
// dissertation shows (Figs. 1.1, 3.5, 6.x) — and a global metric map composed through the
// gateway transforms, written as a ROS map_server PGM + YAML pair.
#pragma once

#include <map>
#include <string>

#include <opencv2/core.hpp>

#include "render/canvas.h"
#include "rgmap/rg_graph.h"
#include "rgmap/rg_map.h"

namespace rgnav::render {

// Frames of all live regions in one global frame: breadth first from the lowest region id
// through the gateways' region_a_from_region_b; a region not connected to it keeps its
// map_from_region.
std::map<int64_t, geometry::Pose2> compose_region_frames(const rgmap::RgMap& map);

Bounds map_bounds(const rgmap::RgMap& map, const std::map<int64_t, geometry::Pose2>& frames);
void draw_rgmap(const rgmap::RgMap& map, const rgmap::RgGraph& graph, Canvas* canvas);
// Renders to path (.svg or .png); pixels per metre 40 by default.
void render_rgmap(const rgmap::RgMap& map, const std::string& path, double pixels_per_metre = 40);

struct GlobalGrid
{
  cv::Mat cells;              // CV_8U: 254 free, 0 occupied, 205 unknown (map_server's trinary PGM)
  double resolution = 0.05;   // [m]
  Eigen::Vector2d origin{0, 0};  // [m] world position of the lower-left cell corner
};

GlobalGrid compose_global_grid(const rgmap::RgMap& map, double resolution);
// Writes <base>.pgm and <base>.yaml; throws std::runtime_error on failure.
void write_map_server(const GlobalGrid& grid, const std::string& base_path);

}  // namespace rgnav::render
