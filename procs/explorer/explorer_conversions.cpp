#include "explorer/explorer_conversions.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cmath>

#include "msg/conversions.h"

namespace rgnav::explorer {

RobotPose to_robot_pose(const slam_pose_t& m)
{
  RobotPose p;
  p.utime = m.utime;
  p.map_from_base = msg::to_pose2(m.map_from_base);
  return p;
}

RobotPose to_robot_pose(const region_pose_t& m)
{
  RobotPose p;
  p.utime = m.utime;
  p.map_from_base = msg::to_pose2(m.map_from_base);
  return p;
}

std::vector<GatewaySighting> to_sightings(const gateway_hypotheses_t& m)
{
  const geometry::Pose2 map_from_base = msg::to_pose2(m.map_from_base);
  std::vector<GatewaySighting> out;
  for (const auto& h : m.hypotheses) {
    const auto cls = static_cast<rgmap::GatewayClass>(h.gateway_class);
    // A plain hallway and a dead end lead nowhere new.
    if (cls == rgmap::GatewayClass::kHallway || cls == rgmap::GatewayClass::kDeadEnd) continue;
    if (h.crossing_points.empty()) continue;
    GatewaySighting s;
    s.cls = cls;
    // A crossing (four corner points, a crossing point per open side): paths cross it in the
    // middle of its square; a passage: at its one crossing point.
    const auto& pts = h.gateway_points.size() == 4 ? h.gateway_points : h.crossing_points;
    Eigen::Vector2d sum(0, 0);
    for (const auto& c : pts) sum += msg::to_vector(c);
    s.crossing = map_from_base * (sum / static_cast<double>(pts.size()));
    for (double d : h.traversal_directions) s.headings.push_back(geometry::normalize_angle(d + map_from_base.theta()));
    s.observations = h.observations;
    out.push_back(std::move(s));
  }
  return out;
}

GoalOutcome to_goal_outcome(int8_t status)
{
  switch (status) {
    case global_path_t::STATUS_NO_PATH: return GoalOutcome::kNoPath;
    case global_path_t::STATUS_GOAL_REACHED: return GoalOutcome::kReached;
    case global_path_t::STATUS_CANCELLED: return GoalOutcome::kCancelled;
    default: return GoalOutcome::kActive;
  }
}

nav_goal_t to_msg(const ExploreGoal& goal, int64_t utime)
{
  nav_goal_t m;
  m.utime = utime;
  m.goal_id = goal.goal_id;
  m.region_id = goal.region_id;
  m.region_name = "";
  m.has_pose = true;
  m.region_from_goal = msg::to_msg(geometry::Pose2(goal.region_point, goal.heading));
  m.position_tolerance = goal.tolerance;
  // Any heading (the robot looks where it drives) but for a look behind.
  m.heading_tolerance = std::min(goal.heading_tolerance, M_PI);
  m.beyond_known = goal.beyond_known;
  m.cancel = false;
  return m;
}

nav_goal_t cancel_msg(int64_t goal_id, int64_t utime)
{
  nav_goal_t m;
  m.utime = utime;
  m.goal_id = goal_id;
  m.region_id = 0;
  m.region_name = "";
  m.has_pose = false;
  m.region_from_goal = msg::to_msg(geometry::Pose2());
  m.position_tolerance = 0.5;
  m.heading_tolerance = M_PI;
  m.beyond_known = false;
  m.cancel = true;
  return m;
}

int8_t to_msg_phase(Phase p)
{
  switch (p) {
    case Phase::kExploring: return explorer_status_t::PHASE_EXPLORING;
    case Phase::kDone: return explorer_status_t::PHASE_DONE;
    case Phase::kWaiting: break;
  }
  return explorer_status_t::PHASE_WAITING;
}

explorer_status_t to_msg(const ExplorerStatus& s, int64_t utime)
{
  explorer_status_t m;
  m.utime = utime;
  m.phase = to_msg_phase(s.phase);
  m.activity = s.activity.substr(0, 256);   // the message's limit (semantic_checks.cpp)
  m.current_region = std::max<int64_t>(0, s.current_region);
  m.current_completeness = std::isfinite(s.current_completeness) ? std::clamp(s.current_completeness, 0.0, 1.0) : 0.0;
  m.regions = std::max(0, s.regions);
  m.complete_regions = std::clamp(s.complete_regions, 0, m.regions);
  m.stack_pending = std::max(0, s.stack_pending);
  m.stack_done = std::max(0, s.stack_done);
  m.stack_set_aside = std::max(0, s.stack_set_aside);
  m.goals_sent = std::max(0, s.goals_sent);
  m.goals_reached = std::max(0, s.goals_reached);
  m.goals_failed = std::max(0, s.goals_failed);
  m.goal_id = s.goal ? std::max<int64_t>(0, s.goal->goal_id) : 0;
  m.goal_region = s.goal ? std::max<int64_t>(0, s.goal->region_id) : 0;
  m.goal_map_point = msg::to_point_msg(s.goal ? s.goal->map_point : Eigen::Vector2d(0, 0));
  return m;
}

std::optional<region_name_request_t> name_request(const rgmap::RgMap& map, int64_t region_id, int64_t utime)
{
  const rgmap::Region* r = map.region(region_id);
  if (!r || r->state == rgmap::Region::State::kMerged) return std::nullopt;
  const auto f = r->freespace.features();
  int gateways = 0;
  for (const auto& [id, g] : map.gateways())
    if (!g.neutralized && (g.region_a == region_id || g.region_b == region_id)) ++gateways;
  // Long and narrow is how a hallway looks; the operator gives the name, this only helps.
  const double major = f.main_axes.x(), minor = f.main_axes.y();
  const char* kind = minor > 0 && major > 3.0 * minor && minor < 3.5 ? "hallway" : "room";
  region_name_request_t m;
  m.utime = utime;
  m.region_id = region_id;
  m.centroid = msg::to_point_msg(f.area > 0 ? r->map_from_region * f.centroid : r->map_from_region.translation());
  m.area = std::max(0.0, f.area);
  m.description = fmt::format("{} {:.0f} m^2 with {} gateway{}", kind, m.area, gateways, gateways == 1 ? "" : "s");
  return m;
}

}  // namespace rgnav::explorer
