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


// A face 2 m ahead coming into view as the robot turns: each scan sees 2 cm more of it. Its
// young points' centroid slides along it like a slow walker.
std::vector<Eigen::Vector2d> face_seen_up_to(double y_end)
{
  std::vector<Eigen::Vector2d> pts;
  for (double y = -0.3; y <= y_end + 1e-9; y += 0.05) pts.push_back({2.0, y});
  return pts;
}

TEST(PeopleTracker, AFaceComingIntoViewIsNoMover)
{
  PeopleTracker tracker(PeopleTrackerOptions{});
  // The newest scan still hits the face where it was first seen.
  const SeenNowFn still_hit = [](const Eigen::Vector2d& p) {
    return std::fabs(p.x() - 2.0) < 0.05 ? SeenNow::kStillThere : SeenNow::kFreeNow;
  };
  time::Time t{};
  for (int k = 0; k < 30; ++k) {
    t = time::from_utime(1'000'000 + k * 26'667);
    tracker.update(t, face_seen_up_to(0.2 + 0.02 * k), still_hit);
  }
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_GT(tracker.tracks()[0].velocity.norm(), PeopleTrackerOptions{}.min_speed);  // it does "move"
  EXPECT_FALSE(tracker.tracks()[0].left_its_place);
  EXPECT_TRUE(tracker.predicted(t).empty());
}

TEST(PeopleTracker, APersonLeavesItsPlaceWalkingAsideOrTowardTheLaser)
{
  for (const SeenNow behind : {SeenNow::kFreeNow, SeenNow::kHidden}) {
    PeopleTracker tracker(PeopleTrackerOptions{});
    const Eigen::Vector2d v = behind == SeenNow::kFreeNow ? Eigen::Vector2d(0.0, 0.8) : Eigen::Vector2d(-0.8, 0.0);
    Eigen::Vector2d centre(3.0, -0.5);
    // The scan hits the person's current arc; where they were is free (walked aside) or
    // hidden behind them (walked toward the laser at the origin).
    const SeenNowFn seen = [&](const Eigen::Vector2d& p) {
      return (p - centre).norm() < 0.25 ? SeenNow::kStillThere : behind;
    };
    time::Time t{};
    for (int k = 0; k < 30; ++k) {
      t = time::from_utime(1'000'000 + k * 26'667);
      centre = Eigen::Vector2d(3.0, -0.5) + v * (k * 0.026667);
      tracker.update(t, person(centre), seen);
    }
    ASSERT_EQ(tracker.tracks().size(), 1u);
    EXPECT_TRUE(tracker.tracks()[0].left_its_place);
    EXPECT_FALSE(tracker.predicted(t).empty());
  }
}

// A person walks for 2 s and stops (their cells turn static: no more young points): the
// track ends, and where it ended is kept (someone who walked up and now waits). A face that
// "moves" for a moment (coming into view) leaves nothing.
TEST(PeopleTracker, RemembersWhereAMoverStopped)
{
  PeopleTrackerOptions o;
  PeopleTracker tracker(o);
  time::Time t{};
  Eigen::Vector2d at(3.0, -1.0);
  for (int k = 0; k < 75; ++k) {  // 2 s at 37.5 Hz, 0.6 m/s
    t = time::from_utime(1'000'000 + k * 26'667);
    at = Eigen::Vector2d(3.0, -1.0) + Eigen::Vector2d(0.0, 0.6) * (k * 0.026667);
    tracker.update(t, person(at));
  }
  EXPECT_TRUE(tracker.last_seen_movers().empty());  // still walking
  t = t + time::Duration(1'000'000);
  tracker.update(t, {});
  ASSERT_EQ(tracker.last_seen_movers().size(), 1u);
  EXPECT_NEAR((tracker.last_seen_movers()[0].position - at).norm(), 0.2, 0.05);  // the arc's centroid
  // Forgotten after stopped_memory.
  tracker.update(t + time::Duration(static_cast<int64_t>((o.stopped_memory + 1.0) * 1e6)), {});
  EXPECT_TRUE(tracker.last_seen_movers().empty());

  PeopleTracker brief(o);
  for (int k = 0; k < 15; ++k) {  // 0.4 s of apparent motion: a face coming into view
    t = time::from_utime(1'000'000 + k * 26'667);
    brief.update(t, person(Eigen::Vector2d(3.0, -1.0) + Eigen::Vector2d(0.0, 0.6) * (k * 0.026667)));
  }
  brief.update(t + time::Duration(1'000'000), {});
  EXPECT_TRUE(brief.last_seen_movers().empty());
}

}  // namespace
}  // namespace rgnav::collision_avoidance
