#include "explorer/explorer_node.h"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "config/config.h"
#include "config/robot_description.h"
#include "explorer/explorer_conversions.h"
#include "explorer/explorer_state.h"
#include "planner/planner_options.h"
#include "rgmap/rgmap_conversions.h"
#include "rgnav/heartbeat_t.hpp"
#include "time/units.h"

namespace rgnav::explorer {

namespace {

using time::kUs;
// No robot is 10 km from the map's origin: such a pose is a corrupted one.
constexpr double kMaxCoordinate = 1e4;
// A goal the planner has not answered (a lost datagram, a planner restarting) is sent again
// this often; a finished region whose name has not come is asked for again this often.
constexpr std::chrono::seconds kResendGoal{2};
constexpr std::chrono::seconds kAskAgain{5};

bool pose_plausible(const pose2d_t& p)
{
  return std::fabs(p.x) <= kMaxCoordinate && std::fabs(p.y) <= kMaxCoordinate && std::fabs(p.theta) <= 100.0;
}

bool point_plausible(const point2d_t& p) { return std::fabs(p.x) <= kMaxCoordinate && std::fabs(p.y) <= kMaxCoordinate; }

}  // namespace

ExplorerNodeConfig load_explorer_node_config(const config::Config& cfg, const config::RobotDescription& robot,
                                             const std::string& config_path)
{
  ExplorerNodeConfig c;
  c.options = load_explorer_node_options(cfg, robot);
  if (!config_path.empty()) {
    // View points are cells of the planner's grid: the planner's own options, not a copy.
    std::filesystem::path planner = c.options.planner_config;
    if (planner.is_relative()) planner = std::filesystem::path(config_path).parent_path() / planner;
    c.options.explorer.grid = planner::load_planner_options(config::Config::load(planner.string()), robot).grid;
  }
  c.pose_fresh_s = cfg.section("pose").number("fresh_s", c.pose_fresh_s, 0.05, 60.0);
  c.step_period_s = cfg.section("step").number("period_s", c.step_period_s, 0.01, 10.0);
  return c;
}

ExplorerNode::ExplorerNode(runtime::Node& node, ExplorerNodeConfig config, ExplorerFiles files)
    : node_(node), config_(std::move(config)), files_(std::move(files)), explorer_(config_.options.explorer)
{
  if (!files_.state_file.empty()) restore();
  const auto& ch = config_.options.channels;
  node_.subscribe<rg_map_t>(ch.rg_map, [this](const rg_map_t& m) { on_map(m); });
  if (!ch.pose.empty()) node_.subscribe<region_pose_t>(ch.pose, [this](const region_pose_t& m) { on_pose(m); });
  if (!ch.slam_pose.empty()) node_.subscribe<slam_pose_t>(ch.slam_pose, [this](const slam_pose_t& m) { on_slam_pose(m); });
  if (!ch.gateway_hypotheses.empty())
    node_.subscribe<gateway_hypotheses_t>(ch.gateway_hypotheses, [this](const gateway_hypotheses_t& m) { on_hypotheses(m); });
  node_.subscribe<global_path_t>(ch.global_path, [this](const global_path_t& m) { on_global_path(m); });
  node_.every(std::chrono::microseconds(static_cast<int64_t>(config_.step_period_s * 1e6)), [this] { step(); });
  node_.every(std::chrono::seconds(1), [this] { publish_status(); });
  node_.every(std::chrono::milliseconds(500), [this] { report(); });
  report();
}

ExplorerNode::~ExplorerNode() { save(true); }

void ExplorerNode::restore()
{
  std::optional<ExplorerState> s;
  try {
    s = load_explorer_state(files_.state_file);
    if (s) explorer_.restore(s->explorer);
  } catch (const std::exception& e) {
    // Kept for a look, out of the way of the next save: a fresh start is better than none.
    const std::string aside = files_.state_file + ".damaged";
    std::error_code ec;
    std::filesystem::rename(files_.state_file, aside, ec);
    spdlog::error("explorer state not used ({}), moved to {}: exploring from scratch", e.what(), aside);
    explorer_ = Explorer(config_.options.explorer);
    return;
  }
  if (!s) {
    spdlog::info("no explorer state in {}: exploring from scratch", files_.state_file);
    return;
  }
  restored_ = true;
  last_saved_utime_ = s->utime;
  saved_text_ = explorer_.save().dump();
  published_phase_ = explorer_.phase();
  const auto& st = explorer_.stack();
  spdlog::info("explorer state from {}: {}, gateway stack {} pending, {} done, {} set aside", files_.state_file,
               to_string(explorer_.phase()), st.count(StackEntry::State::kPending), st.count(StackEntry::State::kDone),
               st.count(StackEntry::State::kSetAside));
}

bool ExplorerNode::observe_time(int64_t utime, const std::string& channel)
{
  const std::string why = clock_.observe(utime, channel);
  if (why.empty()) return true;
  node_.drops().drop(channel, why);
  return false;
}

void ExplorerNode::on_map(const rg_map_t& m)
{
  const std::string& ch = config_.options.channels.rg_map;
  if (m.version == map_version_) return;   // the kernel republishes its map at 1 Hz
  if (!observe_time(m.utime, ch)) return;
  auto map = std::make_shared<rgmap::RgMap>();
  try {
    *map = rgmap::from_msg(m);
  } catch (const std::exception& e) {
    return node_.drops().drop(ch, std::string("RG map refused: ") + e.what());
  }
  // The explorer follows gateways to their regions: a map whose structure does not hold is no
  // map to explore.
  const auto problems = map->consistency_problems();
  if (!problems.empty()) return node_.drops().drop(ch, "RG map refused: " + problems.front());
  if (map_version_ < 0)
    spdlog::info("first RG map: version {}, {} regions, {} gateways", map->version, map->regions().size(),
                 map->gateways().size());
  map_version_ = m.version;
  map_ = map;
  explorer_.set_map(map_);
}

void ExplorerNode::on_pose(const region_pose_t& m)
{
  const std::string& ch = config_.options.channels.pose;
  if (!observe_time(m.utime, ch)) return;
  if (!pose_plausible(m.map_from_base)) return node_.drops().drop(ch, "pose beyond 10 km or |theta| > 100 rad");
  // Confidence 0: the localizer has not converged; its best guess is no place to explore from.
  if (!(m.confidence > 0.f)) return;
  if (m.utime < last_pose_utime_) return;
  last_pose_utime_ = m.utime;
  last_any_pose_utime_ = std::max(last_any_pose_utime_, m.utime);
  explorer_.set_pose(to_robot_pose(m));
}

void ExplorerNode::on_slam_pose(const slam_pose_t& m)
{
  const std::string& ch = config_.options.channels.slam_pose;
  if (!observe_time(m.utime, ch)) return;
  if (!pose_plausible(m.map_from_base)) return node_.drops().drop(ch, "pose beyond 10 km or |theta| > 100 rad");
  // The localizer's pose is preferred while fresh.
  if (last_pose_utime_ > 0 && static_cast<double>(m.utime - last_pose_utime_) * kUs <= config_.pose_fresh_s) return;
  if (m.utime < last_any_pose_utime_) return;
  last_any_pose_utime_ = m.utime;
  explorer_.set_pose(to_robot_pose(m));
}

void ExplorerNode::on_hypotheses(const gateway_hypotheses_t& m)
{
  const std::string& ch = config_.options.channels.gateway_hypotheses;
  if (!observe_time(m.utime, ch)) return;
  if (!pose_plausible(m.map_from_base)) return node_.drops().drop(ch, "pose beyond 10 km or |theta| > 100 rad");
  for (const auto& h : m.hypotheses) {
    const bool far = std::any_of(h.crossing_points.begin(), h.crossing_points.end(), [](const point2d_t& p) { return !point_plausible(p); }) ||
                     std::any_of(h.gateway_points.begin(), h.gateway_points.end(), [](const point2d_t& p) { return !point_plausible(p); });
    if (far) return node_.drops().drop(ch, "gateway point beyond 10 km");
    if (h.observations < 0) return node_.drops().drop(ch, "observations < 0");
    if (std::any_of(h.traversal_directions.begin(), h.traversal_directions.end(), [](double d) { return std::fabs(d) > 100.0; }))
      return node_.drops().drop(ch, "traversal direction |theta| > 100 rad");
  }
  const auto sightings = to_sightings(m);
  if (!sightings.empty()) explorer_.add_sightings(sightings, m.utime);
}

void ExplorerNode::on_global_path(const global_path_t& m)
{
  if (!observe_time(m.utime, config_.options.channels.global_path)) return;
  if (sent_ && m.goal_id == sent_->goal_id) sent_answered_ = true;
  const GoalOutcome outcome = to_goal_outcome(m.status);
  // The planner repeats a final status every second: said once here.
  const bool news = m.goal_id != reported_goal_ || m.status != reported_status_;
  reported_goal_ = m.goal_id;
  reported_status_ = m.status;
  if (news && outcome != GoalOutcome::kActive && sent_ && m.goal_id == sent_->goal_id)
    spdlog::info("goal {}: {}{}", m.goal_id,
                 outcome == GoalOutcome::kReached ? "reached" : outcome == GoalOutcome::kNoPath ? "no path" : "cancelled",
                 m.reason.empty() ? "" : " (" + m.reason + ")");
  explorer_.goal_report(m.goal_id, outcome, m.reason, clock_.now());
}

void ExplorerNode::step()
{
  if (clock_.now() == 0) return;
  const Command c = explorer_.step(clock_.now());
  const auto& ch = config_.options.channels;
  if (c.cancel) {
    spdlog::info("goal {} cancelled", c.cancel_goal_id);
    node_.publish(ch.nav_goal, cancel_msg(c.cancel_goal_id, clock_.now()));
    if (sent_ && sent_->goal_id == c.cancel_goal_id) sent_.reset();
    save_now_ = true;
  }
  if (c.goal) {
    const ExploreGoal& g = *c.goal;
    spdlog::info("goal {}: {} in region {} at ({:.2f}, {:.2f}) map ({:.2f}, {:.2f}){}", g.goal_id,
                 to_string(g.kind),
                 g.region_id, g.region_point.x(), g.region_point.y(), g.map_point.x(), g.map_point.y(),
                 g.beyond_known ? ", beyond the known" : "");
    node_.publish(ch.nav_goal, to_msg(g, clock_.now()));
    sent_ = g;
    sent_answered_ = false;
    sent_wall_ = std::chrono::steady_clock::now();
    save_now_ = true;
  } else if (sent_ && !sent_answered_ && std::chrono::steady_clock::now() - sent_wall_ >= kResendGoal) {
    // Still the running goal: the planner has not heard it (or restarted without it).
    const auto& running = explorer_.goal();
    if (running && running->goal_id == sent_->goal_id) node_.publish(ch.nav_goal, to_msg(*sent_, clock_.now()));
    else sent_.reset();
    sent_wall_ = std::chrono::steady_clock::now();
  }
  const auto now = std::chrono::steady_clock::now();
  for (int64_t id : explorer_.take_finished_regions()) name_requests_.emplace(id, now - kAskAgain);
  // Exploration over: every region still without a name is asked for (also those offered
  // before a restart, whose requests this instance never sent).
  if (explorer_.phase() == Phase::kDone && map_ && map_->version != done_asked_version_) {
    done_asked_version_ = map_->version;
    for (const auto& [id, r] : map_->regions())
      if (r.state != rgmap::Region::State::kMerged && r.name.empty()) name_requests_.emplace(id, now - kAskAgain);
  }
  request_names();
  if (explorer_.phase() != published_phase_) {
    spdlog::info("phase {} -> {}", to_string(published_phase_), to_string(explorer_.phase()));
    published_phase_ = explorer_.phase();
    save_now_ = true;
    publish_status();
  }
  save(false);
}

void ExplorerNode::request_names()
{
  if (!map_ || name_requests_.empty()) return;
  const auto now = std::chrono::steady_clock::now();
  for (auto it = name_requests_.begin(); it != name_requests_.end();) {
    const int64_t live = map_->region(it->first) ? map_->resolve(it->first) : 0;
    const rgmap::Region* r = live ? map_->region(live) : nullptr;
    if (!r || !r->name.empty()) {   // gone, or named (the RG kernel keeps names in its map)
      if (r) spdlog::info("region {} is '{}'", live, r->name);
      it = name_requests_.erase(it);
      continue;
    }
    if (now - it->second >= kAskAgain) {
      if (const auto m = name_request(*map_, live, clock_.now())) {
        node_.publish(config_.options.channels.region_name_request, *m);
        spdlog::info("what is region {} called? ({}, at map ({:.1f}, {:.1f}))", live, m->description, m->centroid.x,
                     m->centroid.y);
      }
      it->second = now;
    }
    ++it;
  }
}

void ExplorerNode::publish_status()
{
  node_.publish(config_.options.channels.status, to_msg(explorer_.status(), clock_.now()));
}

void ExplorerNode::save(bool now)
{
  if (files_.state_file.empty()) return;
  const bool due = save_now_ || clock_.now() < last_saved_utime_ ||
                   static_cast<double>(clock_.now() - last_saved_utime_) * kUs >= config_.options.persist_period_s;
  if (!now && !due) return;
  ExplorerState s;
  s.utime = clock_.now() > 0 ? clock_.now() : last_saved_utime_;
  s.explorer = explorer_.save();
  std::string text = s.explorer.dump();
  save_now_ = false;
  if (text == saved_text_ && !now) {
    last_saved_utime_ = s.utime;
    return;
  }
  try {
    save_explorer_state(files_.state_file, s);
    ++saves_;
    saved_text_ = std::move(text);
    last_saved_utime_ = s.utime;
    if (save_failed_) spdlog::info("saving the explorer state to {} works again", files_.state_file);
    save_failed_ = false;
  } catch (const std::exception& e) {
    if (!save_failed_) spdlog::error("saving the explorer state failed: {}", e.what());
    save_failed_ = true;
  }
}

void ExplorerNode::report()
{
  std::string text = to_string(explorer_.phase());
  if (!map_) text += "; no map yet";
  else if (last_any_pose_utime_ == 0) text += "; no pose yet";
  if (save_failed_) text += "; saving the state fails";
  if (sent_) text += fmt::format("; goal {}", sent_->goal_id);
  if (text.size() > 200) text = text.substr(0, 200);
  const int8_t state = save_failed_ ? heartbeat_t::STATE_DEGRADED : heartbeat_t::STATE_RUNNING;
  if (text == reported_text_ && state == reported_state_) return;
  reported_text_ = text;
  reported_state_ = state;
  node_.set_status(state, text);
}

}  // namespace rgnav::explorer
