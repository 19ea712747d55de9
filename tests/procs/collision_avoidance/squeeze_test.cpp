// A passage narrower than the full clearance (radius + safety margin) on the robot's way, as
// the route planner leads through where the passage allows: collision avoidance goes through
// it slowly with squeeze_margin; without that it stood at the passage's mouth for good.
#include <gtest/gtest.h>

#include <cmath>

#include "collision_avoidance/collision_avoidance.h"
#include "scan_fixture.h"

namespace rgnav::collision_avoidance {
namespace {

using testing::Wall;

// Open space west of x = 0; east of it a passage 0.66 m wide (0.33 m from its centre line to
// either side: more than radius + squeeze margin, less than radius + safety margin), 2 m long,
// opening into open space again.
std::vector<Wall> narrow_passage()
{
  return {{{0.0, -0.33}, {2.0, -0.33}}, {{0.0, 0.33}, {2.0, 0.33}},
          {{0.0, -0.33}, {0.0, -3.0}},  {{0.0, 0.33}, {0.0, 3.0}}};
}

// The first chain collision avoidance sends toward a target beyond the passage (none: nullopt),
// standing at its mouth and looking into it.
std::optional<trajectory::Trajectory> first_chain(const CaOptions& o, std::string* status)
{
  CollisionAvoidance ca(o);
  Targets t;
  t.goal_id = 3;
  t.poses = {Pose2(3.0, 0.0, 0.0)};
  ca.set_targets(t);
  const Pose2 pose(-0.6, 0.0, 0.0);
  int64_t us = 1'000'000;
  for (int i = 0; i < 20; ++i) {
    us += 100'000;
    const time::Time now = time::from_utime(us);
    ca.on_odometry(now, pose, 0.0);
    ca.on_scan(now, testing::cast(pose * o.base_from_laser, narrow_passage()), 8.0);
    ca.on_drive_feedback({0, 0, 0.0, 0.0, 0.0});
    const auto out = ca.update(now);
    *status = ca.status();
    if (out && !out->chain.empty() && ca.mode() == Mode::kPlanned) return out;
  }
  return std::nullopt;
}

double nearest_wall_distance(const Eigen::Vector2d& p)
{
  double best = 1e9;
  for (const auto& w : narrow_passage()) {
    const Eigen::Vector2d ab = w.b - w.a;
    const double t = std::clamp((p - w.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (w.a + t * ab - p).norm());
  }
  return best;
}

TEST(Squeeze, GoesThroughAPassageNarrowerThanTheFullClearanceSlowly)
{
  CaOptions o;
  o.squeeze_margin = 0.05;
  std::string status;
  const auto t = first_chain(o, &status);
  ASSERT_TRUE(t) << status;
  EXPECT_NE(status.find("squeezing"), std::string::npos) << status;
  // Through the passage, never closer to its walls than radius + squeeze margin, slowly.
  EXPECT_GT(t->chain.end().x(), 2.0);
  for (double s = 0.0; s <= t->chain.length(); s += 0.02)
    EXPECT_GE(nearest_wall_distance(t->chain.pose_at(s).translation()),
              o.planner.robot_radius + o.squeeze_margin - 0.005)
        << "at s = " << s;
  for (const auto& seg : t->chain.segments()) EXPECT_LE(seg.v_max(), o.squeeze_speed + 1e-9);
}

TEST(Squeeze, WithoutItNoChainEntersThePassage)
{
  CaOptions o;
  o.squeeze_margin = 0.0;
  std::string status;
  EXPECT_FALSE(first_chain(o, &status)) << status;
}

// With squeeze_people on (off by default): someone walking near by, and a person standing
// still keeps only the plain margin, so the robot does not begin a squeeze while anyone is
// that near (it waits, or the fallbacks take their turn).
TEST(Squeeze, NotBegunWithSomeoneWalkingNearBy)
{
  CaOptions o;
  o.squeeze_margin = 0.05;
  o.squeeze_people = 1.5;
  CollisionAvoidance ca(o);
  const Pose2 pose(-0.6, 0.0, 0.0);
  int64_t us = 1'000'000;
  bool squeezed = false;
  for (int i = 0; i < 40; ++i) {
    us += 100'000;
    const time::Time now = time::from_utime(us);
    // A person (a 0.3 m square) walking at 0.5 m/s toward the passage's mouth, ahead to the
    // left of the robot, stopping 1 m beside it.
    auto walls = narrow_passage();
    const double y = std::max(1.0, 2.5 - 0.05 * i);
    rgnav::testing::add(&walls, rgnav::testing::box(-0.45, y - 0.15, -0.15, y + 0.15));
    ca.on_odometry(now, pose, 0.0);
    ca.on_scan(now, testing::cast(pose * o.base_from_laser, walls), 8.0);
    ca.on_drive_feedback({0, 0, 0.0, 0.0, 0.0});
    if (i == 20) {
      // Targets only once the person is tracked.
      Targets t;
      t.goal_id = 3;
      t.poses = {Pose2(3.0, 0.0, 0.0)};
      ca.set_targets(t);
    }
    ca.update(now);
    if (i >= 20) squeezed = squeezed || ca.status().find("squeezing") != std::string::npos;
  }
  EXPECT_FALSE(squeezed) << ca.status();
}

}  // namespace
}  // namespace rgnav::collision_avoidance
