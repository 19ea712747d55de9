#include "goal_time_budget.h"

namespace rgnav::explore_eval {

void GoalTimeBudget::close_goal(int reached, int failed, const std::string& why)
{
  if (!goal_id_) return;
  KindTime& k = kinds_[kind_];
  if (reached > reached_) {
    k.reached_s += goal_s_;
    ++k.reached;
  } else if (failed > failed_) {
    k.failed_s += goal_s_;
    ++k.failed;
    k.failed_s_by_reason[why] += goal_s_;
  } else {
    // Replaced by a better choice before it ended: neither reached nor failed.
    k.running_s += goal_s_;
  }
  goal_id_.reset();
  goal_s_ = 0;
}

void GoalTimeBudget::step(double t, std::optional<int64_t> goal_id, const std::string& kind, int reached, int failed,
                          const std::string& why, const Eigen::Vector2d& robot)
{
  const double dt = last_t_ ? t - *last_t_ : 0.0;
  const bool still = last_t_ && dt > 0 && (robot - last_robot_).norm() < kStillSpeed * dt;
  last_t_ = t;
  last_robot_ = robot;
  // The time since the last step belongs to the goal that ran then.
  if (goal_id_) {
    goal_s_ += dt;
    if (still) still_with_goal_s_ += dt;
  } else {
    no_goal_s_ += dt;
  }
  if (goal_id != goal_id_) {
    close_goal(reached, failed, why);
    if (goal_id) {
      goal_id_ = goal_id;
      kind_ = kind;
      reached_ = reached;
      failed_ = failed;
    }
  }
}

nlohmann::json GoalTimeBudget::to_json() const
{
  // The goal running at the end counts with the replaced ones.
  std::map<std::string, KindTime> kinds = kinds_;
  if (goal_id_) kinds[kind_].running_s += goal_s_;
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, k] : kinds)
    out[name] = {{"reached_s", k.reached_s}, {"reached", k.reached},   {"failed_s", k.failed_s},
                 {"failed", k.failed},       {"replaced_or_running_s", k.running_s}, {"failed_s_by_reason", k.failed_s_by_reason}};
  return {{"by_kind", out}, {"no_goal_s", no_goal_s_}, {"standing_with_goal_s", still_with_goal_s_}};
}

}  // namespace rgnav::explore_eval
