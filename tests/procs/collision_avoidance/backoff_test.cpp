// Collision avoidance when the robot is already closer to something than its clearance (a
// person who stepped up to it and now waits for it to move): it must turn away and drive
// out, not stand forever.
#include <gtest/gtest.h>

#include "collision_avoidance/collision_avoidance.h"

namespace rgnav::collision_avoidance {
namespace {

// A person-sized arc of readings 0.25 m from the laser, to the front left.
std::vector<PolarReading> person_front_left()
{
  std::vector<PolarReading> r;
  for (int i = -90; i <= 90; ++i) {
    const double b = i * M_PI / 180.0;
    r.push_back({b, (i >= 20 && i <= 50) ? 0.25 : 8.0});
  }
  return r;
}

TEST(BackOff, TurnsAwayThenDrivesOut)
{
  CaOptions o;
  CollisionAvoidance ca(o);
  Targets t;
  t.poses = {Pose2(3.0, 0.0, 0.0)};
  ca.set_targets(t);
  int64_t us = 1'000'000;
  auto feed = [&](const Pose2& pose) {
    ca.on_odometry(time::from_utime(us), pose, 0.0);
    ca.on_scan(time::from_utime(us), person_front_left(), 8.0);
    ca.on_drive_feedback({0, 0, 0.0, 0.0, 0.0});
  };
  // First it stops and waits (the person may walk on).
  feed(Pose2());
  auto first = ca.update(time::from_utime(us));
  ASSERT_TRUE(first);
  EXPECT_TRUE(first->chain.empty());
  EXPECT_EQ(ca.mode(), Mode::kReactive);
  // After the wait: a turn on the spot, away from the person (to the right, i.e. negative).
  std::optional<trajectory::Trajectory> turn;
  for (int i = 0; i < 40 && !(turn && !turn->chain.empty()); ++i) {
    us += 100'000;
    feed(Pose2());
    turn = ca.update(time::from_utime(us));
  }
  ASSERT_TRUE(turn && !turn->chain.empty()) << ca.status();
  ASSERT_EQ(turn->chain[0].kind(), trajectory::Kind::kTurn);
  EXPECT_LT(turn->chain[0].turn_angle(), -1.5);
  EXPECT_NE(ca.status().find("backing off"), std::string::npos) << ca.status();
  // Once facing away (the person now behind, out of the laser's view but still in the
  // local map), it drives a straight line out.
  const double away = turn->chain[0].turn_angle();
  std::optional<trajectory::Trajectory> out;
  for (int i = 0; i < 5 && !(out && !out->chain.empty() && out->chain[0].kind() == trajectory::Kind::kLine); ++i) {
    us += 100'000;
    ca.on_odometry(time::from_utime(us), Pose2(0, 0, away), 0.0);
    ca.on_drive_feedback({turn->id, 2, 0.0, 0.0, 0.0});
    out = ca.update(time::from_utime(us));
  }
  ASSERT_TRUE(out && !out->chain.empty()) << ca.status();
  EXPECT_EQ(out->chain[0].kind(), trajectory::Kind::kLine);
  EXPECT_NEAR(out->chain[0].start().theta(), away, 0.3);
}


// Someone stands 0.6 m ahead across the whole view (a person waiting at their personal space in
// a narrow passage): nothing is within the clearance, so the plain back-off never starts, and
// the person will not walk on while the robot stands there. Without headway for yield_after,
// the robot backs away; the time it stood idle before it had targets does not count.
TEST(BackOff, YieldsAfterNoHeadway)
{
  CaOptions o;
  CollisionAvoidance ca(o);
  std::vector<PolarReading> wall_ahead;
  for (int i = -90; i <= 90; ++i) {
    const double b = i * M_PI / 180.0;
    wall_ahead.push_back({b, std::min(8.0, 0.6 / std::max(0.05, std::cos(b)))});
  }
  int64_t us = 1'000'000;
  // Standing idle first, without targets, longer than yield_after: no lack of headway.
  for (int i = 0; i < 120; ++i) {
    us += 100'000;
    ca.on_odometry(time::from_utime(us), Pose2(), 0.0);
    ca.on_scan(time::from_utime(us), wall_ahead, 8.0);
    ca.update(time::from_utime(us));
  }
  Targets t;
  t.poses = {Pose2(3.0, 0.0, 0.0)};
  ca.set_targets(t);
  bool yielded_early = false, yielded = false;
  for (int i = 0; i < 120 && !yielded; ++i) {
    us += 100'000;
    ca.on_odometry(time::from_utime(us), Pose2(), 0.0);
    ca.on_scan(time::from_utime(us), wall_ahead, 8.0);
    ca.on_drive_feedback({0, 0, 0.0, 0.0, 0.0});
    const auto out = ca.update(time::from_utime(us));
    if (ca.status().find("yielding") != std::string::npos && out && !out->chain.empty()) {
      yielded = true;
      yielded_early = i * 0.1 < o.yield_after - 0.2;
    }
  }
  EXPECT_TRUE(yielded) << ca.status();
  EXPECT_FALSE(yielded_early);
}

}  // namespace
}  // namespace rgnav::collision_avoidance
