#include "planner/planner_node.h"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "config/config.h"
#include "config/robot_description.h"
#include "msg/conversions.h"
#include "planner/planner_conversions.h"
#include "planner/planner_state.h"
#include "rgmap/rgmap_conversions.h"
#include "rgmap/saved_map.h"
#include "rgnav/heartbeat_t.hpp"
#include "time/units.h"

namespace rgnav::planner {

namespace {

using time::kUs;
// No robot is 10 km from its region's origin: such a pose is a corrupted one.
constexpr double kMaxCoordinate = 1e4;
// A final status (reached, cancelled) is repeated this many times (once a second) after its
// first publication, for a tool that missed it.
constexpr int kRepeatFinal = 3;
// Goal and name changes are saved at once, but not more often than this (a flood of goals).
constexpr std::chrono::milliseconds kMinSaveGap{200};

bool pose_plausible(const pose2d_t& p)
{
  return std::fabs(p.x) <= kMaxCoordinate && std::fabs(p.y) <= kMaxCoordinate && std::fabs(p.theta) <= 100.0;
}

bool pursuing(GoalStatus s) { return s == GoalStatus::kActive || s == GoalStatus::kNoPath; }

// [s] expected time left on `route` from `pose` (the leg of its region, projected onto it);
// nullopt when the pose's region is not on the route.
std::optional<double> remaining_s(const Route& route, const RobotPose& pose)
{
  if (route.length <= 0) return std::nullopt;
  for (size_t k = 0; k < route.legs.size(); ++k) {
    const RouteLeg& leg = route.legs[k];
    if (leg.region_id != pose.region_id) continue;
    double distance = 0;
    double left = leg.length - project_onto_leg(leg, pose.region_from_base.translation(), 0.0, &distance);
    for (size_t j = k + 1; j < route.legs.size(); ++j) left += route.legs[j].length;
    return route.cost_s * std::max(0.0, left) / route.length;
  }
  return std::nullopt;
}

}  // namespace

PlannerNodeConfig load_planner_node_config(const config::Config& cfg, const config::RobotDescription& robot)
{
  PlannerNodeConfig c;
  c.options = load_planner_node_options(cfg, robot);
  c.odometry = cfg.section("channels").string("odometry", c.odometry);
  const auto p = cfg.section("pose");
  c.pose.fresh_s = p.number("fresh_s", c.pose.fresh_s, 0.05, 60.0);
  c.odometry_period_s = p.number("odometry_period_s", c.odometry_period_s, 0.0, 10.0);
  return c;
}

PlannerNode::PlannerNode(runtime::Node& node, PlannerNodeConfig config, PlannerFiles files)
    : node_(node),
      config_(std::move(config)),
      files_(std::move(files)),
      planner_(config_.options.planner),
      poses_(config_.pose)
{
  // Planning on a large map takes seconds on a loaded host: the supervisor sees it progressing.
  planner_.global().set_progress([this] { node_.note_progress(); });
  if (!files_.state_file.empty()) restore();
  if (!files_.map.empty()) {
    take_map(rgmap::load_map_flag(files_.map), files_.map);
  } else if (!config_.options.channels.rg_map.empty()) {
    spdlog::info("no saved map given (--map): waiting for {}", config_.options.channels.rg_map);
  }

  const auto& ch = config_.options.channels;
  if (!ch.rg_map.empty()) node_.subscribe<rg_map_t>(ch.rg_map, [this](const rg_map_t& m) { on_map(m); });
  if (!ch.pose.empty()) node_.subscribe<region_pose_t>(ch.pose, [this](const region_pose_t& m) { on_pose(m); });
  if (!ch.slam_pose.empty()) node_.subscribe<slam_pose_t>(ch.slam_pose, [this](const slam_pose_t& m) { on_slam_pose(m); });
  if (!config_.odometry.empty()) node_.subscribe<odometry_t>(config_.odometry, [this](const odometry_t& m) { on_odometry(m); });
  node_.subscribe<nav_goal_t>(ch.nav_goal, [this](const nav_goal_t& m) { on_goal(m); });
  if (!ch.region_name.empty())
    node_.subscribe<region_name_t>(ch.region_name, [this](const region_name_t& m) { on_region_name(m); });
  if (!ch.ca_status.empty()) node_.subscribe<ca_status_t>(ch.ca_status, [this](const ca_status_t& m) { on_ca_status(m); });
  node_.every(std::chrono::milliseconds(100), [this] {
    step();
    save(false);
  });
  node_.every(std::chrono::seconds(1), [this] { republish_path(); });
  node_.every(std::chrono::milliseconds(500), [this] { report(); });
  report();
}

PlannerNode::~PlannerNode() { save(true); }

void PlannerNode::restore()
{
  std::optional<PlannerState> s;
  try {
    s = load_planner_state(files_.state_file);
  } catch (const std::exception& e) {
    // Kept for a look, out of the way of the next save: a fresh start is better than none.
    const std::string aside = files_.state_file + ".damaged";
    std::error_code ec;
    std::filesystem::rename(files_.state_file, aside, ec);
    spdlog::error("planner state not used ({}), moved to {}: starting with nothing learned", e.what(), aside);
    return;
  }
  if (!s) {
    spdlog::info("no planner state in {}: starting with nothing learned", files_.state_file);
    return;
  }
  names_ = s->names;
  if (!s->costs.is_null()) {
    try {
      planner_.global().costs().from_json(s->costs);
    } catch (const std::exception& e) {
      spdlog::error("{}: learned costs not used: {}", files_.state_file, e.what());
    }
  }
  saved_cost_changes_ = planner_.global().costs().changes();
  resume_goal_ = s->goal;
  last_saved_utime_ = s->utime;   // robot time itself comes from the robot, not from the file
  spdlog::info("planner state from {}: {} region names, {}", files_.state_file, names_.size(),
               resume_goal_ ? fmt::format("goal {} to resume", resume_goal_->goal_id) : std::string("no goal"));
}

void PlannerNode::on_map(const rg_map_t& m)
{
  if (m.version == map_version_) return;   // the kernel republishes its map at 1 Hz
  rgmap::RgMap map;
  try {
    map = rgmap::from_msg(m);
  } catch (const std::exception& e) {
    return node_.drops().drop(config_.options.channels.rg_map, std::string("RG map refused: ") + e.what());
  }
  // The planner follows gateways to their regions: a map whose structure does not hold
  // (a gateway to a region that is not there) is no map to plan on.
  const auto problems = map.consistency_problems();
  if (!problems.empty())
    return node_.drops().drop(config_.options.channels.rg_map, "RG map refused: " + problems.front());
  take_map(map, config_.options.channels.rg_map);
}

void PlannerNode::take_map(const rgmap::RgMap& received, const std::string& source)
{
  rgmap::RgMap map = received;
  // Region names: an RG kernel hears REGION_NAME too and keeps names with its map, so its
  // names stand (one it was told while this planner was down is newer than what the planner
  // remembers). A saved map has no keeper but this planner: the names it was told are laid
  // over the file's, where they pick one region.
  const bool kernel_map = source == config_.options.channels.rg_map;
  for (auto it = names_.begin(); it != names_.end();) {
    const int64_t live = map.region(it->first) ? map.resolve(it->first) : 0;
    rgmap::Region* r = live ? map.region(live) : nullptr;
    if (kernel_map && r && !r->name.empty() && r->name != it->second) {
      spdlog::info("region {} is '{}' in the RG map now (was '{}' here)", live, r->name, it->second);
      it = names_.erase(it);
      goal_dirty_ = true;
      continue;
    }
    std::string why;
    if (r && r->name != it->second && rgmap::region_to_name(map, it->first, it->second, &why) == live) r->name = it->second;
    ++it;
  }
  const bool first = !has_map_;
  planner_.set_map(map);
  has_map_ = true;
  map_version_ = map.version;
  if (slam_before_map_) {
    place_slam_pose(*slam_before_map_);
    slam_before_map_.reset();
  }
  spdlog::log(first ? spdlog::level::info : spdlog::level::debug, "map version {} from {}: {} regions, {} gateways",
              map.version, source, map.regions().size(), map.gateways().size());
  if (resume_goal_) {
    const NavGoal g = *resume_goal_;
    resume_goal_.reset();
    planner_.set_goal(g, clock_.now() > 0 ? clock_.now() : last_saved_utime_);
    resumed_goal_ = g;
    spdlog::info("resuming goal {} ({}) from the saved state", g.goal_id,
                 g.region_id ? "region " + std::to_string(g.region_id) : "'" + g.region_name + "'");
    // Said at once, before the first pose: the planner's time is then the one it was saved at.
    if (clock_.now() == 0 && last_saved_utime_ > 0) step_at(last_saved_utime_);
  }
  step();
}

bool PlannerNode::observe_time(int64_t utime, const std::string& channel)
{
  const std::string why = clock_.observe(utime, channel);
  if (why.empty()) return true;
  node_.drops().drop(channel, why);
  return false;
}

void PlannerNode::on_pose(const region_pose_t& m)
{
  const std::string& ch = config_.options.channels.pose;
  if (!observe_time(m.utime, ch)) return;
  if (m.region_id <= 0) return node_.drops().drop(ch, "pose in region id <= 0");
  if (!pose_plausible(m.region_from_base) || !pose_plausible(m.odom_from_base))
    return node_.drops().drop(ch, "pose beyond 10 km or |theta| > 100 rad");
  // Confidence 0: the localizer has not converged (localizing globally); its best guess is no
  // place to plan from.
  if (!(m.confidence > 0.f)) return;
  if (const auto p = poses_.localized(to_robot_pose(m))) take_pose(*p);
}

void PlannerNode::on_slam_pose(const slam_pose_t& m)
{
  const std::string& ch = config_.options.channels.slam_pose;
  if (!observe_time(m.utime, ch)) return;
  if (!pose_plausible(m.map_from_base) || !pose_plausible(m.map_from_odom))
    return node_.drops().drop(ch, "pose beyond 10 km or |theta| > 100 rad");
  // While mapping, the robot is in the RG map's current region. Before the first map the pose
  // is kept for it: a robot standing at its start gets no other from the scan mapper.
  if (!has_map_) {
    slam_before_map_ = m;
    return;
  }
  place_slam_pose(m);
}

void PlannerNode::place_slam_pose(const slam_pose_t& m)
{
  const rgmap::RgMap& map = planner_.global().map();
  const int64_t region = map.resolve(map.current_region);
  const rgmap::Region* r = region ? map.region(region) : nullptr;
  if (!r) return;
  RobotPose fix;
  fix.utime = m.utime;
  fix.region_id = region;
  const geometry::Pose2 map_from_base = msg::to_pose2(m.map_from_base);
  fix.region_from_base = r->map_from_region.inverse() * map_from_base;
  fix.odom_from_base = msg::to_pose2(m.map_from_odom).inverse() * map_from_base;
  if (const auto p = poses_.slam(fix)) take_pose(*p);
}

void PlannerNode::on_odometry(const odometry_t& m)
{
  if (!observe_time(m.utime, config_.odometry)) return;
  if (!pose_plausible(m.odom_from_base)) return node_.drops().drop(config_.odometry, "odometry beyond 10 km or |theta| > 100 rad");
  if (last_odometry_seq_ >= 0 && m.seq < last_odometry_seq_) {
    // A restarted base driver: a new odometry frame, in which no fix held can be carried.
    spdlog::info("odometry sequence went back ({} -> {}): poses are carried again from the next fix", last_odometry_seq_, m.seq);
    poses_.odometry_restarted();
    last_carried_utime_ = 0;
  } else if (m.utime <= last_odometry_utime_) {
    return;   // a duplicate or a late one: nothing newer to carry to
  }
  last_odometry_seq_ = m.seq;
  last_odometry_utime_ = m.utime;
  if (static_cast<double>(m.utime - last_carried_utime_) * kUs < config_.odometry_period_s) return;
  if (const auto p = poses_.odometry(m.utime, msg::to_pose2(m.odom_from_base))) {
    last_carried_utime_ = m.utime;
    take_pose(*p);
  }
}

void PlannerNode::take_pose(const RobotPose& pose)
{
  last_pose_ = pose;
  planner_.on_pose(pose);
  step();
}

void PlannerNode::on_goal(const nav_goal_t& m)
{
  const std::string& ch = config_.options.channels.nav_goal;
  // Operators stamp with wall time: the robot's time decides (it is the planner's clock).
  const int64_t t = clock_.now() > 0 ? clock_.now() : m.utime;
  if (m.cancel) {
    const auto& running = planner_.goal();
    const int64_t id = m.goal_id != 0 ? m.goal_id : (running ? running->goal_id : 0);
    if (!running || running->goal_id != id || !pursuing(planner_.status())) {
      spdlog::info("cancel of goal {}: not the goal pursued", m.goal_id);
      return;
    }
    spdlog::info("goal {} cancelled", id);
    planner_.cancel(id, t);
  } else {
    if (m.goal_id <= 0) return node_.drops().drop(ch, "goal_id must be > 0");
    // The goal pursued, said again (a tool repeating itself until the planner answers, a
    // duplicated datagram): nothing changes, nothing to log or save.
    const auto& running = planner_.goal();
    if (running && running->goal_id == m.goal_id && planner_.status() == GoalStatus::kActive) return;
    const NavGoal goal = to_nav_goal(m);
    spdlog::info("goal {}: {}{}", goal.goal_id,
                 goal.region_id ? "region " + std::to_string(goal.region_id) : "'" + goal.region_name + "'",
                 goal.has_pose ? fmt::format(" at ({:.2f}, {:.2f}, {:.0f} deg)", goal.region_from_goal.x(),
                                             goal.region_from_goal.y(), goal.region_from_goal.theta() * 180 / M_PI)
                               : std::string(", anywhere suitable"));
    resume_goal_.reset();   // an operator's goal replaces a saved one not yet taken up
    planner_.set_goal(goal, t);
  }
  goal_dirty_ = true;
  // Before any robot input the goal's own stamp is the only time there is: the answer (no
  // pose or no map yet) must still reach the operator.
  step_at(t);
  save(false);
  report();
}

void PlannerNode::on_region_name(const region_name_t& m)
{
  const std::string& ch = config_.options.channels.region_name;
  int64_t id = m.region_id;
  if (has_map_) {
    std::string why;
    id = rgmap::region_to_name(planner_.global().map(), m.region_id, m.name, &why);
    if (id == 0) return node_.drops().drop(ch, "region name refused: " + why);
  }
  // Without a map the name cannot be checked against one: it is kept, and laid over the map
  // once one arrives (where it picks one region).
  const auto known = names_.find(id);
  if (known != names_.end() && known->second == m.name) return;
  names_[id] = m.name;
  if (has_map_) planner_.name_region(id, m.name);
  spdlog::info("region {} named '{}'", id, m.name);
  goal_dirty_ = true;
  save(false);
}

void PlannerNode::on_ca_status(const ca_status_t& m)
{
  if (!observe_time(m.utime, config_.options.channels.ca_status)) return;
  const auto& goal = planner_.goal();
  // Only collision avoidance's state on this planner's targets says anything about its route.
  if (!goal || m.goal_id != goal->goal_id) return;
  planner_.on_blocked(clock_.now(), cannot_pass(m));
}

void PlannerNode::step()
{
  if (clock_.now() > 0) step_at(clock_.now());
}

void PlannerNode::step_at(int64_t utime)
{
  const GoalStatus before = planner_.status();
  const auto out = planner_.update(utime);
  if (out.path) {
    const PathReport& r = *out.path;
    const GoalStatus after = r.status;
    if (after != before || !last_path_ || last_path_->goal_id != r.goal_id || r.reason != last_path_->reason) {
      const auto level = after == GoalStatus::kNoPath ? spdlog::level::warn : spdlog::level::info;
      spdlog::log(level, "goal {} {}{}: {} legs, {:.1f} m, {:.0f} s left, {} replans", r.goal_id, to_string(after),
                  r.reason.empty() ? "" : " (" + r.reason + ")", r.route.legs.size(), r.route.length, r.remaining_s,
                  r.replans);
    }
    last_path_ = r;
    republish_after_end_ = pursuing(r.status) ? 0 : kRepeatFinal;
    node_.publish(config_.options.channels.global_path,
                  to_msg(r, r.route.map_version ? r.route.map_version : map_version_));
    if (!pursuing(after) || after != before) goal_dirty_ = true;
  }
  if (out.targets) node_.publish(config_.options.channels.targets, to_msg(*out.targets));
}

void PlannerNode::republish_path()
{
  if (!last_path_) return;
  const bool active = planner_.goal() && planner_.goal()->goal_id == last_path_->goal_id && pursuing(planner_.status());
  if (!active) {
    if (republish_after_end_ <= 0) return;
    --republish_after_end_;
  }
  PathReport r = *last_path_;
  if (clock_.now() > r.utime) r.utime = clock_.now();
  if (active && r.status == GoalStatus::kActive && last_pose_)
    if (const auto left = remaining_s(r.route, *last_pose_)) r.remaining_s = *left;
  node_.publish(config_.options.channels.global_path, to_msg(r, r.route.map_version ? r.route.map_version : map_version_));
}

void PlannerNode::save(bool now)
{
  if (files_.state_file.empty()) return;
  const int64_t changes = planner_.global().costs().changes();
  const bool learned = changes != saved_cost_changes_;
  if (!now) {
    if (!goal_dirty_ && !learned) return;
    if (std::chrono::steady_clock::now() - last_save_wall_ < kMinSaveGap) return;   // the timer saves it soon
    const bool costs_due = learned && (clock_.now() < last_saved_utime_ ||
                                       static_cast<double>(clock_.now() - last_saved_utime_) * kUs >= config_.options.persist_period_s);
    if (!goal_dirty_ && !costs_due) return;
  }
  PlannerState s;
  s.utime = clock_.now() > 0 ? clock_.now() : last_saved_utime_;
  s.costs = planner_.global().costs().to_json();
  s.names = names_;
  if (resume_goal_) s.goal = resume_goal_;
  else if (planner_.goal() && pursuing(planner_.status())) s.goal = planner_.goal();
  try {
    save_planner_state(files_.state_file, s);
    ++saves_;
    goal_dirty_ = false;
    saved_cost_changes_ = changes;
    last_saved_utime_ = s.utime;
    last_save_wall_ = std::chrono::steady_clock::now();
    if (save_failed_) spdlog::info("saving the planner state to {} works again", files_.state_file);
    save_failed_ = false;
  } catch (const std::exception& e) {
    if (!save_failed_) spdlog::error("saving the planner state failed: {}", e.what());
    save_failed_ = true;
    last_save_wall_ = std::chrono::steady_clock::now();
  }
}

void PlannerNode::report()
{
  const auto& goal = planner_.goal();
  const GoalStatus status = planner_.status();
  std::string text;
  if (!goal || status == GoalStatus::kNone) {
    text = "no goal";
  } else {
    text = fmt::format("goal {} {}", goal->goal_id, to_string(status));
    if (status == GoalStatus::kActive && last_path_ && !last_path_->route.empty())
      text += fmt::format(", {} legs", last_path_->route.legs.size());
    text += fmt::format(", {} replans", planner_.replans());
    if (last_path_ && last_path_->goal_id == goal->goal_id && !last_path_->reason.empty() && status != GoalStatus::kActive)
      text += ": " + last_path_->reason;
  }
  if (!has_map_) text += "; no map yet";
  const bool pose_stale = !last_pose_ || static_cast<double>(clock_.now() - last_pose_->utime) * kUs >
                                             config_.options.planner.execution.pose_timeout_s;
  if (goal && status == GoalStatus::kActive && pose_stale) text += "; no fresh pose";
  if (save_failed_) text += "; saving the state fails";
  if (text.size() > 200) text = text.substr(0, 200);
  const bool degraded = !has_map_ || save_failed_ || (goal && status == GoalStatus::kActive && pose_stale);
  const int8_t state = degraded ? heartbeat_t::STATE_DEGRADED : heartbeat_t::STATE_RUNNING;
  if (text == reported_text_ && state == reported_state_) return;
  reported_text_ = text;
  reported_state_ = state;
  node_.set_status(state, text);
}

}  // namespace rgnav::planner
