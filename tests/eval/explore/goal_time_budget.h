// Where an explorer's time goes, for the benchmark: simulated seconds spent on goals of each kind
// that were reached, that failed (by the reason the explorer gave) and that ran at the end, with
// no goal at all, and standing still while a goal ran (held by collision avoidance, yielding to a
// person, waiting for a path). Fed once per simulation step; knows nothing of the explorer.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <string>

namespace rgnav::explore_eval {

class GoalTimeBudget
{
 public:
  // `goal_id` and `kind`: the goal running at `t` [s] (none: nullopt); `reached` and `failed`: the
  // explorer's counters of goals ended so far; `why`: what it said when the last goal ended.
  void step(double t, std::optional<int64_t> goal_id, const std::string& kind, int reached, int failed,
            const std::string& why, const Eigen::Vector2d& robot);
  nlohmann::json to_json() const;

 private:
  struct KindTime
  {
    double reached_s = 0, failed_s = 0, running_s = 0;
    int reached = 0, failed = 0;
    std::map<std::string, double> failed_s_by_reason;
  };
  void close_goal(int reached, int failed, const std::string& why);

  static constexpr double kStillSpeed = 0.03;   // [m/s] slower than this the robot stands
  std::map<std::string, KindTime> kinds_;
  std::optional<int64_t> goal_id_;
  std::string kind_;
  double goal_s_ = 0;                 // time of the running goal so far
  int reached_ = 0, failed_ = 0;      // the counters when it began
  double no_goal_s_ = 0, still_with_goal_s_ = 0;
  std::optional<double> last_t_;
  Eigen::Vector2d last_robot_{0, 0};
};

}  // namespace rgnav::explore_eval
