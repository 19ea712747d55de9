#include "rgmap/saved_map.h"

#include <filesystem>
#include <optional>
#include <stdexcept>

#include "config/config.h"
#include "persist/checked_json.h"
#include "rgmap/rgmap_json.h"

namespace rgnav::rgmap {

std::string saved_map_file(const std::string& path)
{
  return std::filesystem::is_directory(path) ? path + "/rgmap.json" : path;
}

RgMap load_map_flag(const std::string& path)
{
  try {
    return load_saved_map(path);
  } catch (const std::exception& e) {
    throw config::ConfigError(std::string("--map: ") + e.what());
  }
}

RgMap load_saved_map(const std::string& path)
{
  const std::string file = saved_map_file(path);
  std::optional<nlohmann::json> doc;
  try {
    doc = persist::read_checked_json(file);
  } catch (const std::exception& e) {
    throw std::runtime_error(e.what());   // CorruptFile names the file and the defect
  }
  if (!doc) throw std::runtime_error(file + ": no such file");
  try {
    return from_json(*doc);
  } catch (const std::exception& e) {
    throw std::runtime_error(file + ": not an RG map: " + e.what());
  }
}

void save_map(const RgMap& map, const std::string& path)
{
  // The same form the RG kernel exports, so render, map and the processes read it alike.
  persist::write_json_atomically(saved_map_file(path), to_json(map));
}

}  // namespace rgnav::rgmap
