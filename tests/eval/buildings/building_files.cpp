#include "building_files.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>

namespace rgnav::buildings {

namespace {

// Pixel corner (x, y) in the world frame (sim/image_world.h: rows grow downwards).
nlohmann::json world_point(const Building& b, double x, double y)
{
  return {x * kMetresPerPixel, (b.height - y) * kMetresPerPixel};
}

// The names sim::rooms_from_segmentation gives the rooms: room_<k> in the order of the 4-connected
// components of the free segmentation pixels (row-major first pixel), those of >= 1 m^2 only.
std::vector<std::string> segmentation_names(const Building& b, const BuildingImages& im)
{
  cv::Mat comp;
  const int n = cv::connectedComponents(im.segmentation > 250, comp, 4, CV_32S);
  std::vector<int> area(static_cast<size_t>(n), 0), label(static_cast<size_t>(n), 0);
  for (int y = 0; y < comp.rows; ++y)
    for (int x = 0; x < comp.cols; ++x) {
      const int k = comp.at<int32_t>(y, x);
      ++area[static_cast<size_t>(k)];
      label[static_cast<size_t>(k)] = im.labels.at<int32_t>(y, x);
    }
  std::vector<std::string> names(b.spaces.size());
  const int min_area = static_cast<int>(1.0 / (kMetresPerPixel * kMetresPerPixel));
  int next = 1;
  for (int k = 1; k < n; ++k) {
    if (area[static_cast<size_t>(k)] < min_area) continue;
    const int l = label[static_cast<size_t>(k)];
    if (l > 0) names[static_cast<size_t>(l - 1)] = "room_" + std::to_string(next);
    ++next;
  }
  return names;
}

void write_png(const std::string& path, const cv::Mat& image)
{
  if (!cv::imwrite(path, image)) throw std::runtime_error(path + ": cannot write");
}

}  // namespace

std::string building_stem(uint64_t seed) { return "rand_" + std::to_string(seed); }

nlohmann::json building_json(const Building& b, const BuildingImages& im)
{
  nlohmann::json j;
  j["seed"] = b.seed;
  j["layout"] = b.layout;
  j["resolution_m"] = kMetresPerPixel;
  j["size_px"] = {b.width, b.height};
  const auto names = segmentation_names(b, im);
  j["rooms"] = nlohmann::json::array();
  for (size_t i = 0; i < b.spaces.size(); ++i) {
    nlohmann::json r;
    r["index"] = i;
    r["kind"] = to_string(b.spaces[i].kind);
    r["segmentation_name"] = names[i];
    for (const auto& pr : b.spaces[i].rects)
      r["rects_m"].push_back({world_point(b, pr.x0, pr.y1), world_point(b, pr.x1, pr.y0)});   // lower-left, upper-right
    j["rooms"].push_back(r);
  }
  j["doorways"] = nlohmann::json::array();
  for (const auto& d : b.doorways) {
    const double line = d.line;
    nlohmann::json e;
    e["rooms"] = {d.a, d.b};
    e["width_m"] = d.width_px() * kMetresPerPixel;
    e["wide_opening"] = d.wide;
    e["points_m"] = d.vertical ? nlohmann::json{world_point(b, line, d.from), world_point(b, line, d.to)}
                               : nlohmann::json{world_point(b, d.from, line), world_point(b, d.to, line)};
    j["doorways"].push_back(e);
  }
  std::set<std::pair<int, int>> edges;
  for (const auto& d : b.doorways) edges.insert({std::min(d.a, d.b), std::max(d.a, d.b)});
  j["graph_edges"] = nlohmann::json::array();
  for (const auto& [a, c] : edges) j["graph_edges"].push_back({a, c});
  return j;
}

size_t count_buildings(const std::vector<std::string>& map_paths)
{
  static const std::string kFurnished = "_furnitures";
  std::set<std::string> buildings;
  for (std::string path : map_paths) {
    if (const auto k = path.rfind(kFurnished); k != std::string::npos) path.erase(k, kFurnished.size());
    buildings.insert(path);
  }
  return buildings.size();
}

void write_building(const Building& b, const BuildingImages& im, const std::string& dir)
{
  std::filesystem::create_directories(dir);
  const std::string base = dir + "/" + building_stem(b.seed);
  write_png(base + ".png", im.map);
  write_png(base + "_furnitures.png", im.furnished);
  write_png(base + "_gt_segmentation.png", im.segmentation);
  std::ofstream f(base + ".json");
  f << building_json(b, im).dump(1) << "\n";
  if (!f) throw std::runtime_error(base + ".json: cannot write");
}

}  // namespace rgnav::buildings
