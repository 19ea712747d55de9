// The demo's job in-process: the office world's whole tour, driven as the demo drives it
// (office_tour.h), with the people starting 14 s late. Before the tour runner named its goals
// and collision avoidance let its turns and back-offs run to their end, the robot stood in
// hall_a from t = 511 s for the remaining 990 s of this run, between walker_a and walker_b who
// waited for it; the demo stopped the same way twice. With those fixed but people who wait
// for the robot for good (no `patience`), it was herded along hall_a for 181 s.
#include <gtest/gtest.h>

#include "collision_avoidance/ca_options.h"
#include "config/config.h"
#include "lld/lld_options.h"
#include "office_tour.h"
#include "sim/tour_planner.h"
#include "sim/world_yaml.h"

namespace rgnav::bench {
namespace {

TEST(OfficeTour, TheRobotGetsPastThePeopleInTheHallways)
{
  const std::string config = std::string(RGNAV_SOURCE_DIR) + "/config/";
  const auto lo = lld::load_lld_options(config::Config::load(config + "lld.yaml"));
  const auto co = collision_avoidance::load_ca_options(config::Config::load(config + "collision_avoidance.yaml"));
  const sim::World world = sim::load_world(config + "worlds/office.yaml");
  const sim::Tour tour = sim::plan_tour(world, sim::RobotOptions{});
  ASSERT_TRUE(tour.collision_free);
  TourRunOptions o;
  o.seed = 1003;
  o.people_delay_s = 14.0;
  o.time_limit_s = 1200.0;
  const TourRunResult r = run_tour(world, tour.waypoints, lo, co.ca, o);
  EXPECT_TRUE(r.completed()) << r.reached << "/" << r.targets << " targets";
  EXPECT_EQ(r.collisions, 0);
  // Waiting for people is fine; standing for minutes is not.
  EXPECT_LT(r.longest_stall_s, 120.0) << "stood at " << r.stall_at.transpose() << " for target " << r.stall_target;
}

}  // namespace
}  // namespace rgnav::bench
