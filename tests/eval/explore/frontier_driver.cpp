// The frontier baseline as an ExploreDriver (explore_drivers.h).
#include <sstream>

#include "explore_drivers.h"

namespace rgnav::explore_eval {

namespace {

class FrontierDriver final : public ExploreDriver
{
 public:
  FrontierDriver(const FrontierOptions& options, const geometry::Pose2& base_from_laser, double max_speed)
      : explorer_(options), base_from_laser_(base_from_laser), max_speed_(max_speed)
  {
  }

  std::string method() const override { return "frontier"; }

  void on_aligned(rgmap_pipeline::RgMapPipeline& pipeline) override
  {
    const auto* n = pipeline.last_aligned();
    if (n) explorer_.add_scan(n->map_from_base, base_from_laser_, n->scan);
  }

  std::optional<collision_avoidance::Targets> step(const PipelineView& view) override
  {
    const auto d = explorer_.step(static_cast<double>(view.utime) * 1e-6, view.map_from_base, view.cannot_pass);
    if (!d.new_targets) return std::nullopt;
    const geometry::Pose2 odom_from_map = view.odom_from_base * view.map_from_base.inverse();
    collision_avoidance::Targets t;
    t.goal_id = d.goal_id;
    for (const auto& p : d.map_targets) t.poses.push_back(odom_from_map * p);
    t.max_speed = max_speed_;
    t.final_is_goal = true;
    return t;
  }

  bool done() const override { return explorer_.done(); }
  std::string trace_line() const override { return explorer_.activity(); }
  nlohmann::json stats() const override
  {
    return {{"goals", explorer_.goals()},
            {"blacklisted", explorer_.blacklisted()},
            {"no_path", explorer_.no_path()},
            {"cpu_s", explorer_.cpu_s()},
            {"end", explorer_.activity()}};
  }

 private:
  FrontierExplorer explorer_;
  geometry::Pose2 base_from_laser_;
  double max_speed_;
};

}  // namespace

std::unique_ptr<ExploreDriver> make_frontier_driver(const FrontierOptions& options, const geometry::Pose2& base_from_laser,
                                                    double max_speed)
{
  return std::make_unique<FrontierDriver>(options, base_from_laser, max_speed);
}

}  // namespace rgnav::explore_eval
