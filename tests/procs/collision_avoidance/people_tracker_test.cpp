#include "collision_avoidance/people_tracker.h"

#include <gtest/gtest.h>

namespace rgnav::collision_avoidance {
namespace {

// A person (a small arc of points) at `centre`.
std::vector<Eigen::Vector2d> person(const Eigen::Vector2d& centre)
{
  std::vector<Eigen::Vector2d> pts;
  for (int i = -3; i <= 3; ++i) pts.push_back(centre + Eigen::Vector2d(-0.2 * std::cos(i * 0.2), 0.2 * std::sin(i * 0.2)));
  return pts;
}

TEST(PeopleTracker, WalkingPersonPredictsAlongItsVelocity)
{
  PeopleTrackerOptions o;
  PeopleTracker tracker(o);
  const Eigen::Vector2d v(0.0, 0.8);
  time::Time t{};
  for (int k = 0; k < 30; ++k) {  // 0.8 s at 37.5 Hz
    t = time::from_utime(1'000'000 + k * 26'667);
    tracker.update(t, person(Eigen::Vector2d(3.0, -1.0) + v * (k * 0.026667)));
  }
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_NEAR(tracker.tracks()[0].velocity.x(), 0.0, 0.05);
  EXPECT_NEAR(tracker.tracks()[0].velocity.y(), 0.8, 0.05);
  const auto pred = tracker.predicted(t);
  ASSERT_FALSE(pred.empty());
  double max_y = -10.0;
  for (const auto& p : pred) max_y = std::max(max_y, p.y());
  const double now_y = -1.0 + 0.8 * 29 * 0.026667;
  EXPECT_NEAR(max_y, now_y + 0.8 * o.horizon + 0.2 * std::sin(0.6), 0.1);
}

TEST(PeopleTracker, StandingStillPredictsNothingAndLostTracksEnd)
{
  PeopleTracker tracker(PeopleTrackerOptions{});
  time::Time t{};
  for (int k = 0; k < 30; ++k) {
    t = time::from_utime(1'000'000 + k * 26'667);
    tracker.update(t, person({2.0, 0.5}));
  }
  EXPECT_TRUE(tracker.predicted(t).empty());
  tracker.update(t + time::Duration(1'000'000), {});
  EXPECT_TRUE(tracker.tracks().empty());
}

TEST(PeopleTracker, TwoPeopleKeepTheirOwnTracks)
{
  PeopleTracker tracker(PeopleTrackerOptions{});
  time::Time t{};
  for (int k = 0; k < 30; ++k) {
    t = time::from_utime(1'000'000 + k * 26'667);
    auto a = person(Eigen::Vector2d(2.0, -1.0) + Eigen::Vector2d(0.0, 0.6) * (k * 0.026667));
    const auto b = person(Eigen::Vector2d(4.0, 1.0) + Eigen::Vector2d(0.0, -0.6) * (k * 0.026667));
    a.insert(a.end(), b.begin(), b.end());
    tracker.update(t, a);
  }
  ASSERT_EQ(tracker.tracks().size(), 2u);
  for (const auto& tr : tracker.tracks()) EXPECT_NEAR(std::fabs(tr.velocity.y()), 0.6, 0.05);
  EXPECT_LT(tracker.tracks()[0].velocity.y() * tracker.tracks()[1].velocity.y(), 0.0);
}

}  // namespace
}  // namespace rgnav::collision_avoidance
