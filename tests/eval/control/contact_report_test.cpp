// ContactHistory: splits the closing of the gap between the robot and a person into whose
// motion closed it (control_bench's contact report).
#include "contact_report.h"

#include <gtest/gtest.h>

namespace rgnav::bench {
namespace {

TEST(ContactHistory, RobotDrivingIntoAStandingPerson)
{
  ContactHistory h;
  for (int i = 0; i <= 20; ++i) h.add(0.05 * i, {0.3 * 0.05 * i, 0.0}, {{1.0, 0.0}});
  const auto s = h.split(0, 1.0, 0.48);
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->window_s, 1.0, 1e-9);
  EXPECT_NEAR(s->robot_closing_m, 0.3, 1e-9);
  EXPECT_NEAR(s->person_closing_m, 0.0, 1e-9);
  EXPECT_NEAR(s->gap_before_m, 1.0 - 0.48, 1e-9);
  EXPECT_EQ(s->closed_by, "robot");
}

TEST(ContactHistory, PersonWalkingIntoARobotBackingAway)
{
  ContactHistory h;
  // The robot backs off at 0.1 m/s, the person walks at it at 0.8 m/s from the side.
  for (int i = 0; i <= 40; ++i) {
    const double t = 0.05 * i;
    h.add(t, {-0.1 * t, 0.0}, {{0.0, 2.5 - 0.8 * t}, {5.0, 5.0}});
  }
  const auto s = h.split(0, 1.0, 0.48);
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->person_closing_m, 0.8, 0.02);
  EXPECT_LT(s->robot_closing_m, 0.05);  // moving away sideways: next to nothing toward them
  EXPECT_EQ(s->closed_by, "person");
  EXPECT_NEAR(s->person_speed_mps, 0.8, 1e-6);
  EXPECT_FALSE(h.split(2, 1.0, 0.48).has_value());  // no such person
}

TEST(ContactHistory, BothAndNeither)
{
  ContactHistory both;
  for (int i = 0; i <= 20; ++i) both.add(0.05 * i, {0.2 * 0.05 * i, 0.0}, {{2.0 - 0.2 * 0.05 * i, 0.0}});
  EXPECT_EQ(both.split(0, 1.0, 0.48)->closed_by, "both");
  ContactHistory still;
  for (int i = 0; i <= 20; ++i) still.add(0.05 * i, {0.0, 0.0}, {{0.6, 0.0}});
  EXPECT_EQ(still.split(0, 1.0, 0.48)->closed_by, "neither");
  // Only the kept history counts: a 5 s memory cannot answer for more.
  ContactHistory longer(1.0);
  for (int i = 0; i <= 100; ++i) longer.add(0.05 * i, {0.01 * i, 0.0}, {{3.0, 0.0}});
  EXPECT_LE(longer.split(0, 3.0, 0.48)->window_s, 1.0 + 1e-9);
}

}  // namespace
}  // namespace rgnav::bench
