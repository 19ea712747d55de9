#include "collision_avoidance/reactive.h"

#include <gtest/gtest.h>

#include "scan_fixture.h"

namespace rgnav::collision_avoidance {
namespace {

TEST(Reactive, FreespaceOrientationPointsToTheOpening)
{
  // Wall ahead at 1 m except an opening on the left (bearings 20..60 deg see far).
  std::vector<PolarReading> r;
  for (int i = -90; i <= 90; ++i) {
    const double b = i * M_PI / 180.0;
    r.push_back({b, (i >= 20 && i <= 60) ? 8.0 : 1.0});
  }
  ReactiveOptions o;
  const double a = freespace_orientation(r, o);
  EXPECT_GT(a, 0.2);
  EXPECT_LT(a, 1.1);
  // Symmetric free space: straight ahead.
  std::vector<PolarReading> open;
  for (int i = -90; i <= 90; ++i) open.push_back({i * M_PI / 180.0, 8.0});
  EXPECT_NEAR(freespace_orientation(open, o), 0.0, 1e-9);
}

TEST(Reactive, SlowsStopsAndTurns)
{
  ReactiveOptions o;
  const auto far = testing::cast(geometry::Pose2(), {{{1.2, -2}, {1.2, 2}}});  // wall 1.2 m ahead
  const ReactiveDecision moving = decide(far, 0.0, false, o);
  EXPECT_EQ(moving.action, ReactiveDecision::Action::kDrive);
  EXPECT_LT(moving.speed, o.v_max);  // slowed down inside dto_max
  const auto near = testing::cast(geometry::Pose2(), {{{0.4, -2}, {0.4, 2}}, {{-1, 2}, {3, 2}}});
  EXPECT_EQ(decide(near, 0.0, false, o).action, ReactiveDecision::Action::kStop);
  const ReactiveDecision standing = decide(near, 0.0, true, o);
  EXPECT_EQ(standing.action, ReactiveDecision::Action::kTurn);
  EXPECT_NE(standing.heading, 0.0);
}

}  // namespace
}  // namespace rgnav::collision_avoidance
