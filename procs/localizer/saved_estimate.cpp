#include "localizer/saved_estimate.h"

#include <nlohmann/json.hpp>

#include <cmath>

#include "persist/checked_json.h"

namespace rgnav::localizer {

namespace {
constexpr const char* kSchema = "rgnav-localizer-estimate";
}

void save_estimate(const std::string& path, const SavedEstimate& e)
{
  nlohmann::json j;
  j["schema"] = kSchema;
  j["utime"] = e.utime;
  j["region"] = e.region;
  j["region_from_base"] = {e.region_from_base.x(), e.region_from_base.y(), e.region_from_base.theta()};
  j["map_from_base"] = {e.map_from_base.x(), e.map_from_base.y(), e.map_from_base.theta()};
  j["map_version"] = e.map_version;
  persist::write_json_atomically(path, j, -1);
}

std::optional<SavedEstimate> load_estimate(const std::string& path, std::string* problem)
{
  try {
    const auto doc = persist::read_checked_json(path);
    if (!doc) return std::nullopt;
    const auto& j = *doc;
    if (j.at("schema").get<std::string>() != kSchema) throw std::invalid_argument("not a localizer estimate");
    const auto pose = [&](const char* key) {
      const auto& a = j.at(key);
      const double x = a.at(0).get<double>(), y = a.at(1).get<double>(), t = a.at(2).get<double>();
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(t)) throw std::invalid_argument(std::string(key) + " not finite");
      return geometry::Pose2(x, y, t);
    };
    SavedEstimate e;
    e.utime = j.at("utime").get<int64_t>();
    e.region = j.at("region").get<int64_t>();
    e.region_from_base = pose("region_from_base");
    e.map_from_base = pose("map_from_base");
    e.map_version = j.at("map_version").get<int64_t>();
    if (e.region <= 0) throw std::invalid_argument("region id not positive");
    return e;
  } catch (const std::exception& ex) {
    if (problem) *problem = path + ": " + ex.what();
    return std::nullopt;
  }
}

}  // namespace rgnav::localizer
