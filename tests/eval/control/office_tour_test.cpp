// The demo's job in-process: the office world's whole tour, driven as the demo drives it
// (office_tour.h), with the people starting 14 s late. The demo stopped for good twice, in a
// doorway and in hall_a, before collision avoidance let its turns and back-offs run to their
// end and the tour runner named its goals (on the tour planned at the default margin, this run
// then stood in hall_a from t = 511 s to the time limit). With those fixed but people who wait
// for the robot for good (no `patience` in the world), this run stands in hall_a at
// (17.1, 12.5) for more than 120 s and the test fails.
#include <gtest/gtest.h>

#include "collision_avoidance/ca_options.h"
#include "config/config.h"
#include "lld/lld_options.h"
#include "office_tour.h"
#include "sim/world_yaml.h"

namespace rgnav::bench {
namespace {

TEST(OfficeTour, TheRobotGetsPastThePeopleInTheHallways)
{
  const std::string config = std::string(RGNAV_SOURCE_DIR) + "/config/";
  const auto robot = config::load_robot_description_file(config + "robot.yaml");
  const auto lo = lld::load_lld_options(config::Config::load(config + "lld.yaml"), robot);
  const auto co = collision_avoidance::load_ca_options(config::Config::load(config + "collision_avoidance.yaml"), robot);
  const sim::World world = sim::load_world(config + "worlds/office.yaml");
  const std::vector<Eigen::Vector2d> tour = demo_tour(world);
  ASSERT_FALSE(tour.empty());
  TourRunOptions o;
  o.seed = 1003;
  o.people_delay_s = 14.0;
  o.time_limit_s = 1200.0;
  const TourRunResult r = run_tour(world, tour, lo, co.ca, o);
  EXPECT_TRUE(r.completed()) << r.reached << "/" << r.targets << " targets";
  EXPECT_EQ(r.collisions, 0);
  // Waiting for people is fine; standing for minutes is not.
  EXPECT_LT(r.longest_stall_s, 120.0) << "stood at " << r.stall_at.transpose() << " for target " << r.stall_target;
}

}  // namespace
}  // namespace rgnav::bench
