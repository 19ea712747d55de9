// rgnav's explorer and planner as an ExploreDriver (explore_drivers.h). Messages between them go
// through the nodes' own conversions (GATEWAY_HYPOTHESES, NAV_GOAL, GLOBAL_PATH's status), so the
// benchmark sees what the live processes see.
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "bench_stats.h"
#include "explore_drivers.h"
#include "explorer/explorer.h"
#include "explorer/explorer_conversions.h"
#include "goal_time_budget.h"
#include "gateway_detector/gateway_conversions.h"
#include "planned_drive.h"
#include "planner/planner.h"
#include "planner/planner_conversions.h"
#include "rgmap/rgmap_json.h"

namespace rgnav::explore_eval {

namespace {

using geometry::Pose2;

const char* kind_name(explorer::ExploreGoal::Kind k) { return explorer::to_string(k); }

class RgDriver final : public ExploreDriver
{
 public:
  RgDriver(const planner::PlannerOptions& planner, const explorer::ExplorerOptions& explorer, double map_period_s)
      : planner_(planner), explorer_(explorer), map_period_s_(map_period_s)
  {
  }

  std::string method() const override { return "rgnav"; }

  void on_aligned(rgmap_pipeline::RgMapPipeline& pipeline) override
  {
    const auto& d = pipeline.last_detection();
    const double c0 = localize_eval::thread_cpu();
    const auto sightings = explorer::to_sightings(gateway_detector::to_hypotheses_msg(d));
    if (!sightings.empty()) explorer_.add_sightings(sightings, d.utime);
    explorer_cpu_s_ += localize_eval::thread_cpu() - c0;
  }

  std::optional<collision_avoidance::Targets> step(const PipelineView& v) override
  {
    const double t = static_cast<double>(v.utime) * 1e-6;
    // RG_MAP: a new version, at most once per map period.
    const auto& live = v.pipeline.kernel().map();
    if (live.current_region != 0 && live.version != map_version_ && t - last_map_s_ >= map_period_s_) {
      auto map = std::make_shared<const rgmap::RgMap>(v.pipeline.refreshed_map());
      last_map_s_ = t;
      map_version_ = live.version;
      if (map->consistency_problems().empty()) {
        map_ = map;
        ++maps_;
        const double c0 = localize_eval::thread_cpu();
        explorer_.set_map(map_);
        explorer_cpu_s_ += localize_eval::thread_cpu() - c0;
        const double c1 = localize_eval::thread_cpu();
        planner_.set_map(*map_);
        planner_cpu_s_ += localize_eval::thread_cpu() - c1;
      } else {
        ++maps_refused_;
      }
    }
    if (!map_) return std::nullopt;
    const double c0 = localize_eval::thread_cpu();
    explorer_.set_pose({v.utime, v.map_from_base});
    // The planner's pose: the SLAM pose in the map's current region, as its node places SLAM_POSE.
    const int64_t region = map_->resolve(map_->current_region);
    if (const rgmap::Region* r = map_->region(region)) {
      last_pose_ = {v.utime, region, r->map_from_region.inverse() * v.map_from_base, v.odom_from_base};
      planner_.on_pose(last_pose_);
    }
    planner_.on_blocked(v.utime, v.cannot_pass);
    const auto o = planner_.update(v.utime);
    planner_cpu_s_ += localize_eval::thread_cpu() - c0;
    bool ended = false;
    const double c2 = localize_eval::thread_cpu();
    if (o.path) {
      const auto outcome = explorer::to_goal_outcome(planner::to_msg_status(o.path->status));
      explorer_.goal_report(o.path->goal_id, outcome, o.path->reason, v.utime);
      if (outcome != explorer::GoalOutcome::kActive) {
        ended = true;
        if (trace_) std::cerr << "  goal " << o.path->goal_id << " " << planner::to_string(o.path->status) << ": " << o.path->reason << "\n";
        if (outcome == explorer::GoalOutcome::kNoPath) {
          ++no_path_;
          if (no_path_reasons_.size() < 20) no_path_reasons_.push_back(o.path->reason);
          dump_no_path(o.path->goal_id, o.path->reason);
        }
      }
    }
    // The node looks at the explorer's decision every step period (0.2 s); it decides on its own
    // period unless a goal ended.
    if (ended || t - last_step_s_ >= kStepPeriod) {
      last_step_s_ = t;
      const explorer::Command c = explorer_.step(v.utime);
      if (trace_) trace_stack_changes(t);
      if (c.cancel) planner_.cancel(c.cancel_goal_id, v.utime);
      if (c.goal) {
        const auto& g = *c.goal;
        ++goals_by_kind_[kind_name(g.kind)];
        if (trace_) {
          std::cerr << std::fixed << std::setprecision(2) << "  goal " << g.goal_id << ": " << kind_name(g.kind) << " in region "
                    << g.region_id << " at (" << g.region_point.x() << ", " << g.region_point.y() << ") map ("
                    << g.map_point.x() << ", " << g.map_point.y() << ")" << (g.beyond_known ? " beyond the known" : "") << "\n";
        }
        const planner::NavGoal nav = planner::to_nav_goal(explorer::to_msg(g, v.utime));
        if (!dump_dir_.empty()) sent_[nav.goal_id] = {nav, g};
        planner_.set_goal(nav, v.utime);
      }
    }
    explorer_cpu_s_ += localize_eval::thread_cpu() - c2;
    {
      const auto& g = explorer_.goal();
      const auto s = explorer_.goal_counts();
      const std::string& end = explorer_.last_end();
      budget_.step(t, g ? std::optional<int64_t>(g->goal_id) : std::nullopt, g ? kind_name(g->kind) : "", s.first, s.second,
                   end.substr(0, end.find(':')), v.map_from_base.translation());
    }
    if (o.targets) {
      // For the trace: what collision avoidance was last given, seen from the robot.
      last_targets_.clear();
      for (const auto& p : o.targets->odom_from_target) last_targets_.push_back((v.odom_from_base.inverse() * p).translation());
      last_final_is_goal_ = o.targets->final_is_goal;
      return plan_eval::to_ca_targets(*o.targets);
    }
    return std::nullopt;
  }

  bool done() const override { return explorer_.phase() == explorer::Phase::kDone; }

  std::string trace_line() const override
  {
    const auto s = explorer_.status();
    std::ostringstream out;
    out << std::fixed << std::setprecision(2) << explorer::to_string(s.phase) << " '" << s.activity << "' region "
        << s.current_region << " completeness " << s.current_completeness << " regions " << s.complete_regions << "/"
        << s.regions << " stack " << s.stack_pending << "/" << s.stack_done << "/" << s.stack_set_aside << " goals "
        << s.goals_reached << "/" << s.goals_sent << " planner " << planner::to_string(planner_.status());
    if (s.goal)
      out << " goal " << s.goal->goal_id << " " << kind_name(s.goal->kind) << " map (" << s.goal->map_point.x() << ", "
          << s.goal->map_point.y() << ")" << (s.goal->beyond_known ? " beyond" : "");
    if (!planner_.route().empty()) {
      out << " route";
      for (const auto& leg : planner_.route().legs) out << " r" << leg.region_id;
    }
    out << " targets (robot frame, when sent)";
    for (const auto& p : last_targets_) out << " (" << p.x() << ", " << p.y() << ")";
    if (last_final_is_goal_) out << " goal";
    return out.str();
  }

  nlohmann::json stats() const override
  {
    const auto s = explorer_.status();
    nlohmann::json j = {{"phase", explorer::to_string(s.phase)},
                        {"activity", s.activity},
                        {"regions", s.regions},
                        {"complete_regions", s.complete_regions},
                        {"stack_pending", s.stack_pending},
                        {"stack_done", s.stack_done},
                        {"stack_set_aside", s.stack_set_aside},
                        {"goals_sent", s.goals_sent},
                        {"goals_reached", s.goals_reached},
                        {"goals_failed", s.goals_failed},
                        {"goals_by_kind", goals_by_kind_},
                        {"no_path_reports", no_path_},
                        {"no_path_reasons", no_path_reasons_},
                        {"maps", maps_},
                        {"maps_refused", maps_refused_},
                        {"planner_replans", planner_.replans()},
                        {"explorer_cpu_s", explorer_cpu_s_},
                        {"planner_cpu_s", planner_cpu_s_},
                        {"time_budget", budget_.to_json()}};
    nlohmann::json aside = nlohmann::json::array();
    for (const auto& e : explorer_.stack().entries())
      if (e.state == explorer::StackEntry::State::kSetAside)
        aside.push_back({{"id", e.id}, {"crossing", {e.crossing.x(), e.crossing.y()}}, {"reason", e.reason}, {"attempts", e.attempts}});
    j["set_aside"] = aside;
    // Traced runs keep the whole stack (every entry's state and reason) for a look afterwards.
    if (trace_) {
      j["stack"] = explorer_.stack().to_json();
      // What is left: every live region's open frontiers (map frame) and the explorer's state.
      nlohmann::json left = nlohmann::json::array();
      if (map_)
        for (const auto& [id, r] : map_->regions()) {
          if (r.state == rgmap::Region::State::kMerged) continue;
          for (const auto& f : explorer_.open_frontiers(id)) {
            const Eigen::Vector2d at = r.map_from_region * f.goal;
            const Eigen::Vector2d out = r.map_from_region.rotation() * f.outward;
            left.push_back({{"region", id}, {"at", {at.x(), at.y()}}, {"outward", {out.x(), out.y()}}, {"width", f.width},
                            {"cells", f.cells.size()}});
          }
        }
      j["frontiers_left"] = left;
      j["explorer_state"] = explorer_.save();
    }
    return j;
  }

  void set_trace(bool on) { trace_ = on; }

 private:
  // The trace: each stack entry that changed state since the last step, with its reason and the
  // regions (and their states) that hold the places beyond it as free.
  void trace_stack_changes(double t)
  {
    for (const auto& e : explorer_.stack().entries()) {
      const auto it = traced_states_.find(e.id);
      if (it != traced_states_.end() && it->second == e.state) continue;
      traced_states_[e.id] = e.state;
      std::cerr << std::fixed << std::setprecision(2) << "  stack t=" << t << " entry " << e.id << " class "
                << static_cast<int>(e.cls) << " at (" << e.crossing.x() << ", " << e.crossing.y() << ") heading "
                << e.heading << " -> " << static_cast<int>(e.state) << " " << e.reason;
      if (map_) {
        for (const double k : {1.0, 2.0}) {
          std::cerr << " | beyond " << k << ":";
          for (const auto& [id, r] : map_->regions())
            if (r.state != rgmap::Region::State::kMerged && r.freespace.width() > 0 &&
                r.freespace.is_free(r.map_from_region.inverse() * e.beyond(k)))
              std::cerr << " r" << id << "/" << static_cast<int>(r.state);
        }
        std::cerr << " | current r" << map_->current_region;
      }
      std::cerr << "\n";
    }
  }
  std::map<int64_t, explorer::StackEntry::State> traced_states_;

  // EXPLORE_DUMP_NO_PATH=DIR: every goal the planner found no path for, with the map and the
  // robot's pose it planned on, as DIR/no_path_<n>.json (tests/eval/plan: rgnav_plan_replay).
  void dump_no_path(int64_t goal_id, const std::string& reason)
  {
    const auto it = sent_.find(goal_id);
    if (dump_dir_.empty() || it == sent_.end() || !map_) return;
    const auto& [g, explore_goal] = it->second;
    // What the goal is for, map frame: the stack entry's crossing, or the frontier looked at.
    Eigen::Vector2d looked_at = explore_goal.frontier_point;
    if (const auto* e = explore_goal.kind == explorer::ExploreGoal::Kind::kGateway ? explorer_.stack().entry(explore_goal.entry_id) : nullptr)
      looked_at = e->crossing;
    const auto pose = [](const geometry::Pose2& p) { return nlohmann::json{p.x(), p.y(), p.theta()}; };
    const nlohmann::json j = {{"reason", reason},
                              {"utime", last_pose_.utime},
                              {"pose", {{"region", last_pose_.region_id}, {"region_from_base", pose(last_pose_.region_from_base)}}},
                              {"goal", {{"goal_id", g.goal_id}, {"region", g.region_id}, {"region_from_goal", pose(g.region_from_goal)},
                                        {"position_tolerance", g.position_tolerance}, {"beyond_known", g.beyond_known},
                                        {"kind", kind_name(explore_goal.kind)}, {"looked_at_map", {looked_at.x(), looked_at.y()}}}},
                              {"map", rgmap::to_json(*map_)}};
    std::filesystem::create_directories(dump_dir_);
    std::ofstream(dump_dir_ + "/no_path_" + std::to_string(++dumps) + ".json") << j.dump();
  }

  // Empty (unset or set to ""): no dumps, and no goals kept for them.
  const std::string dump_dir_ = std::getenv("EXPLORE_DUMP_NO_PATH") ? std::getenv("EXPLORE_DUMP_NO_PATH") : "";
  static inline std::atomic<int> dumps{0};   // runs at once share the folder
  std::map<int64_t, std::pair<planner::NavGoal, explorer::ExploreGoal>> sent_;
  planner::RobotPose last_pose_;
  static constexpr double kStepPeriod = 0.2;   // [s] config/explorer.yaml step.period_s
  planner::Planner planner_;
  explorer::Explorer explorer_;
  double map_period_s_;
  std::shared_ptr<const rgmap::RgMap> map_;
  int64_t map_version_ = -1;
  double last_map_s_ = -1e9, last_step_s_ = -1e9;
  int maps_ = 0, maps_refused_ = 0, no_path_ = 0;
  std::vector<std::string> no_path_reasons_;
  std::map<std::string, int> goals_by_kind_;
  double explorer_cpu_s_ = 0, planner_cpu_s_ = 0;
  bool trace_ = std::getenv("EXPLORE_TRACE") != nullptr;
  std::vector<Eigen::Vector2d> last_targets_;
  bool last_final_is_goal_ = false;
  GoalTimeBudget budget_;
};

}  // namespace

std::unique_ptr<ExploreDriver> make_rg_driver(const planner::PlannerOptions& planner, const explorer::ExplorerOptions& explorer,
                                              double map_period_s)
{
  return std::make_unique<RgDriver>(planner, explorer, map_period_s);
}

}  // namespace rgnav::explore_eval
