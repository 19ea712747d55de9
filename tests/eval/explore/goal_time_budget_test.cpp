// The explore bench's time budget: seconds go to the goal that ran, by how it ended.
#include <gtest/gtest.h>

#include "goal_time_budget.h"

namespace rgnav::explore_eval {
namespace {

using Eigen::Vector2d;

TEST(GoalTimeBudget, SecondsGoToTheGoalThatRanByHowItEnded)
{
  GoalTimeBudget b;
  // 0-10 s: frontier goal 1, driving 0.1 m/s, reached.
  for (int k = 0; k <= 10; ++k) b.step(k, 1, "frontier", 0, 0, "", Vector2d(0.1 * k, 0));
  // 10-30 s: gateway goal 2 standing still; it failed for no progress by the step at 30 s (the
  // time since a step belongs to what ran at that step).
  b.step(10, 2, "gateway", 1, 0, "reached", Vector2d(1, 0));
  for (int k = 11; k <= 29; ++k) b.step(k, 2, "gateway", 1, 0, "reached", Vector2d(1, 0));
  // 30-35 s: no goal; 35-40 s: frontier goal 3, moving, still running at the end.
  for (int k = 30; k <= 34; ++k) b.step(k, std::nullopt, "", 1, 1, "no progress", Vector2d(1, 0));
  for (int k = 35; k <= 40; ++k) b.step(k, 3, "frontier", 1, 1, "no progress", Vector2d(1 + 0.1 * (k - 34), 0));
  const nlohmann::json j = b.to_json();
  EXPECT_DOUBLE_EQ(j["by_kind"]["frontier"]["reached_s"].get<double>(), 10.0);
  EXPECT_EQ(j["by_kind"]["frontier"]["reached"].get<int>(), 1);
  EXPECT_DOUBLE_EQ(j["by_kind"]["gateway"]["failed_s"].get<double>(), 20.0);
  EXPECT_DOUBLE_EQ(j["by_kind"]["gateway"]["failed_s_by_reason"]["no progress"].get<double>(), 20.0);
  EXPECT_DOUBLE_EQ(j["by_kind"]["frontier"]["replaced_or_running_s"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(j["no_goal_s"].get<double>(), 5.0);
  // Standing with a goal: the gateway's 20 s.
  EXPECT_DOUBLE_EQ(j["standing_with_goal_s"].get<double>(), 20.0);
}

}  // namespace
}  // namespace rgnav::explore_eval
