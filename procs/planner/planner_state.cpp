#include "planner/planner_state.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "persist/atomic_file.h"
#include "rgmap/region_name.h"

namespace rgnav::planner {

namespace {

constexpr const char* kSchema = "rgnav.planner_state";
constexpr int kSchemaVersion = 1;

nlohmann::json goal_to_json(const NavGoal& g)
{
  return {{"goal_id", g.goal_id},
          {"region_id", g.region_id},
          {"region_name", g.region_name},
          {"has_pose", g.has_pose},
          {"region_from_goal", {g.region_from_goal.x(), g.region_from_goal.y(), g.region_from_goal.theta()}},
          {"position_tolerance", g.position_tolerance},
          {"heading_tolerance", g.heading_tolerance}};
}

double finite(const nlohmann::json& j, const char* key)
{
  const double v = j.at(key).get<double>();
  if (!std::isfinite(v)) throw std::invalid_argument(std::string(key) + " is not finite");
  return v;
}

NavGoal goal_from_json(const nlohmann::json& j)
{
  NavGoal g;
  g.goal_id = j.at("goal_id").get<int64_t>();
  g.region_id = j.at("region_id").get<int64_t>();
  g.region_name = j.at("region_name").get<std::string>();
  g.has_pose = j.at("has_pose").get<bool>();
  const auto& p = j.at("region_from_goal");
  if (!p.is_array() || p.size() != 3) throw std::invalid_argument("region_from_goal is not [x, y, theta]");
  const double x = p[0].get<double>(), y = p[1].get<double>(), th = p[2].get<double>();
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(th)) throw std::invalid_argument("region_from_goal is not finite");
  g.region_from_goal = geometry::Pose2(x, y, th);
  g.position_tolerance = finite(j, "position_tolerance");
  g.heading_tolerance = finite(j, "heading_tolerance");
  // The same rules as a goal on NAV_GOAL (semantic_checks.cpp): a saved goal is one that was taken.
  if (g.goal_id <= 0) throw std::invalid_argument("goal_id must be > 0");
  if (g.region_id < 0 || (g.region_id == 0 && g.region_name.empty())) throw std::invalid_argument("goal needs a region id or name");
  if (g.region_name.size() > rgmap::kMaxRegionNameLength) throw std::invalid_argument("region_name too long");
  if (!(g.position_tolerance > 0) || !(g.heading_tolerance > 0)) throw std::invalid_argument("tolerances must be > 0");
  return g;
}

}  // namespace

void save_planner_state(const std::string& path, const PlannerState& s)
{
  nlohmann::json j;
  j["schema"] = kSchema;
  j["schema_version"] = kSchemaVersion;
  j["utime"] = s.utime;
  j["costs"] = s.costs;
  auto names = nlohmann::json::array();
  for (const auto& [id, name] : s.names) names.push_back({{"region", id}, {"name", name}});
  j["names"] = names;
  j["goal"] = s.goal ? goal_to_json(*s.goal) : nlohmann::json();
  const auto dir = std::filesystem::path(path).parent_path();
  if (!dir.empty()) std::filesystem::create_directories(dir);
  persist::write_atomically(path, j.dump(1));
}

std::optional<PlannerState> load_planner_state(const std::string& path)
{
  std::optional<std::string> text;
  try {
    text = persist::read_checked(path);
  } catch (const std::exception& e) {
    throw std::runtime_error(e.what());   // CorruptFile names the file and the defect
  }
  if (!text) return std::nullopt;
  try {
    const auto j = nlohmann::json::parse(*text);
    if (j.at("schema").get<std::string>() != kSchema) throw std::invalid_argument("schema is not " + std::string(kSchema));
    if (j.at("schema_version").get<int>() != kSchemaVersion) throw std::invalid_argument("unknown schema_version");
    PlannerState s;
    s.utime = j.at("utime").get<int64_t>();
    s.costs = j.at("costs");
    for (const auto& n : j.at("names")) {
      const int64_t id = n.at("region").get<int64_t>();
      const std::string name = n.at("name").get<std::string>();
      std::string why;
      if (id <= 0) throw std::invalid_argument("names: region id must be > 0");
      if (!rgmap::valid_region_name(name, &why)) throw std::invalid_argument("names: " + why);
      s.names[id] = name;
    }
    if (!j.at("goal").is_null()) s.goal = goal_from_json(j.at("goal"));
    return s;
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": not a planner state: " + e.what());
  }
}

}  // namespace rgnav::planner
