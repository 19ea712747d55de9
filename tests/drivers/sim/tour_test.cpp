#include <gtest/gtest.h>

#include <set>

#include "sim/tour_planner.h"
#include "sim/waypoint_follower.h"
#include "sim/world_yaml.h"

namespace rgnav::sim {
namespace {

TEST(Tour, OfficeTourEntersEveryReachableRoomWithoutCollision)
{
  World world = load_world(std::string(RGNAV_SOURCE_DIR) + "/config/worlds/office.yaml");
  const RobotOptions robot;
  const Tour tour = plan_tour(world, robot);
  ASSERT_TRUE(tour.collision_free);
  EXPECT_GE(polyline_clearance(world, robot, tour.waypoints), robot.radius);
  // office_e4's door is closed at the start: the only unreachable region.
  EXPECT_EQ(tour.unreachable, std::vector<std::string>{"office_e4"});
  const std::set<std::string> visited(tour.visited.begin(), tour.visited.end());
  for (const auto& r : world.regions)
    if (r.name != "office_e4") {
      EXPECT_TRUE(visited.count(r.name)) << r.name << " not visited";
    }
  // A closed loop.
  EXPECT_LT((tour.waypoints.front() - tour.waypoints.back()).norm(), 1e-9);

  // Drive it: the simulated robot follows the waypoints without touching anything (people
  // removed: they are not obstacles the planner knows of) and its true path enters every room.
  world.people.clear();
  SimulatorOptions options;
  options.laser_enabled = false;
  options.physics_step = std::chrono::microseconds(5000);
  Simulator sim(world, options);
  WaypointFollower follower(tour.waypoints, [&sim] { return sim.truth(); });
  sim.set_command_source(&follower);
  std::vector<Vec2> path;
  int64_t collisions = 0;
  for (int k = 0; k < 20000 && !follower.done(); ++k) {
    const StepOutput out = sim.step(std::chrono::microseconds(100'000));
    for (const auto& o : out.odometry) path.emplace_back(o.world_from_base.x, o.world_from_base.y);
    collisions += static_cast<int64_t>(out.collisions.size());
  }
  EXPECT_TRUE(follower.done()) << "stuck before waypoint " << follower.next_index();
  EXPECT_EQ(collisions, 0);
  const auto driven = regions_along(world, path);
  const std::set<std::string> entered(driven.begin(), driven.end());
  for (const auto& r : world.regions)
    if (r.kind == RegionKind::kRoom && r.name != "office_e4") {
      EXPECT_TRUE(entered.count(r.name)) << r.name;
    }
}

TEST(Tour, HallwayWorldTourIsCollisionFree)
{
  const World world = load_world(std::string(RGNAV_SOURCE_DIR) + "/config/worlds/hallways_2m_strongly_cluttered.yaml");
  const Tour tour = plan_tour(world, RobotOptions{});
  EXPECT_TRUE(tour.collision_free);
  EXPECT_TRUE(tour.unreachable.empty());
}

TEST(Tour, LapsRouteGoesRoundAgainFromTheStartWithoutRepeatingIt)
{
  Tour tour;
  tour.waypoints = {{0, 0}, {2, 0}, {2, 1}, {0, 0}};
  EXPECT_TRUE(laps_route(tour, 0).empty());
  const auto one = laps_route(tour, 1);
  ASSERT_EQ(one.size(), 4u);
  const auto three = laps_route(tour, 3);
  ASSERT_EQ(three.size(), 10u);   // 4, then 3 more a lap: the start is not visited twice in a row
  for (size_t i = 0; i < three.size(); ++i) EXPECT_EQ(three[i], tour.waypoints[i == 0 ? 0 : (i - 1) % 3 + 1]) << i;
}

}  // namespace
}  // namespace rgnav::sim
