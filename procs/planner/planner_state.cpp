#include "planner/planner_state.h"

#include <cmath>
#include <stdexcept>

#include "persist/json_state.h"
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
          {"heading_tolerance", g.heading_tolerance},
          {"beyond_known", g.beyond_known}};
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
  g.beyond_known = j.value("beyond_known", false);   // absent in state files written before it existed
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
  j["utime"] = s.utime;
  j["costs"] = s.costs;
  auto names = nlohmann::json::array();
  for (const auto& [id, name] : s.names) names.push_back({{"region", id}, {"name", name}});
  j["names"] = names;
  j["goal"] = s.goal ? goal_to_json(*s.goal) : nlohmann::json();
  persist::write_json_state(path, kSchema, kSchemaVersion, std::move(j));
}

std::optional<PlannerState> load_planner_state(const std::string& path)
{
  const auto doc = persist::read_json_state(path, kSchema, kSchemaVersion, "a planner");
  if (!doc) return std::nullopt;
  const nlohmann::json& j = *doc;
  try {
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
    throw persist::not_this_state(path, "a planner", e);
  }
}

}  // namespace rgnav::planner
