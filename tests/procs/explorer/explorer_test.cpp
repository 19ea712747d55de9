// The explorer's algorithm library on hand-made RG maps: where a region's freespace ends in the
// unknown, the gateway stack's order and bookkeeping, and the explorer's goals region by region
// up to its end, across a restart.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "explorer/explorer.h"
#include "explorer/frontiers.h"
#include "explorer/gateway_stack.h"
#include "explorer/opening.h"
#include "explorer/place_view.h"
#include "explorer/view_gain.h"
#include "box_region.h"

namespace rgnav::explorer {
namespace {

using Eigen::Vector2d;
using geometry::Pose2;
using V = Vector2d;
using Wall = std::pair<V, V>;

constexpr int64_t kUtime = 1'700'000'000'000'000;
constexpr int64_t kSecond = 1'000'000;

// A region whose frame is the map frame shifted to `lo`: walls (map frame) as its line map and
// freespace at 0.15 m over the box [lo, hi] (map frame).
rgmap::Region& add_region(rgmap::RgMap* map, const V& lo, const V& hi, const std::vector<Wall>& walls)
{
  return testing::add_box_region(map, lo, hi, walls, 0.15, kUtime);
}

// A hallway [0, 6] x [0, 1.8]: walls along both sides and the left end; the right end open
// unless `closed`; a 1 m door in the north wall centred at x = `door_x` if that is given.
std::shared_ptr<rgmap::RgMap> hallway(bool closed, std::optional<double> door_x = std::nullopt)
{
  auto map = std::make_shared<rgmap::RgMap>();
  std::vector<Wall> walls = {{V(0, 0), V(6, 0)}, {V(0, 0), V(0, 1.8)}};
  if (door_x) {
    walls.push_back({V(0, 1.8), V(*door_x - 0.5, 1.8)});
    walls.push_back({V(*door_x + 0.5, 1.8), V(6, 1.8)});
  } else {
    walls.push_back({V(0, 1.8), V(6, 1.8)});
  }
  if (closed) walls.push_back({V(6, 0), V(6, 1.8)});
  map->current_region = add_region(map.get(), V(0, 0), V(6, 1.8), walls).id;
  map->version = 1;
  return map;
}

TEST(Frontiers, AnOpenEndIsAFrontierAndAWalledOneIsNot)
{
  const auto open = hallway(false);
  const RegionFrontiers f = find_frontiers(*open, open->current_region, FrontierOptions{});
  ASSERT_EQ(f.frontiers.size(), 1u);
  EXPECT_NEAR(f.frontiers[0].centroid.x(), 5.9, 0.1);
  EXPECT_GT(f.frontiers[0].outward.x(), 0.9);
  EXPECT_NEAR(f.frontiers[0].width, 1.8, 0.2);
  EXPECT_LT(f.completeness(), 0.95);

  const auto closed = hallway(true);
  const RegionFrontiers g = find_frontiers(*closed, closed->current_region, FrontierOptions{});
  EXPECT_TRUE(g.frontiers.empty());
  EXPECT_DOUBLE_EQ(g.completeness(), 1.0);
}

TEST(Frontiers, SpaceKnownFromAnotherRegionIsNoFrontier)
{
  auto map = hallway(false);
  add_region(map.get(), V(6, 0), V(9, 1.8), {{V(6, 0), V(9, 0)}, {V(6, 1.8), V(9, 1.8)}, {V(9, 0), V(9, 1.8)}});
  EXPECT_TRUE(find_frontiers(*map, map->current_region, FrontierOptions{}).frontiers.empty());
  EXPECT_TRUE(known_free(*map, V(7, 1)));
  EXPECT_FALSE(known_free(*map, V(10, 1)));
}

TEST(Frontiers, AGapNarrowerThanMinWidthIsAShadow)
{
  // The right end walled but for a 0.3 m gap: too narrow for a frontier.
  auto map = std::make_shared<rgmap::RgMap>();
  map->current_region = add_region(map.get(), V(0, 0), V(6, 1.8),
                                   {{V(0, 0), V(6, 0)}, {V(0, 1.8), V(6, 1.8)}, {V(0, 0), V(0, 1.8)},
                                    {V(6, 0), V(6, 0.6)}, {V(6, 1.5), V(6, 1.8)}})
                           .id;
  FrontierOptions o;
  const RegionFrontiers wide = find_frontiers(*map, map->current_region, o);
  ASSERT_EQ(wide.frontiers.size(), 1u) << "a 0.9 m opening is a frontier";
  o.min_width = 1.2;
  EXPECT_TRUE(find_frontiers(*map, map->current_region, o).frontiers.empty());
  EXPECT_GT(find_frontiers(*map, map->current_region, o).frontier_cells, 0) << "a shadow still counts as incomplete";
}

// A look past the hallway's open end sees the whole fan unknown; with the hallway beyond it
// known as another region, nothing; a wall across the fan hides what lies behind it.
TEST(ViewGain, TheFanSeesWhatNoRegionHoldsUpToTheFirstWall)
{
  GainOptions o;   // 2 m rays, +-1 rad: a fan of 4 m^2
  auto map = hallway(false);
  const double open = unknown_area_beyond(*map, V(5.95, 0.9), V(1, 0), o);
  EXPECT_GT(open, 3.5);
  EXPECT_LT(open, 4.2);
  auto walled = hallway(false);
  walled->region(walled->current_region)->segments.push_back({V(6.5, -2), V(6.5, 4), 0.01, 50});
  EXPECT_LT(unknown_area_beyond(*walled, V(5.95, 0.9), V(1, 0), o), 1.0) << "the fan ends 0.55 m on";
  add_region(map.get(), V(6, 0), V(9, 1.8), {{V(6, 0), V(9, 0)}, {V(6, 1.8), V(9, 1.8)}, {V(9, 0), V(9, 1.8)}});
  EXPECT_LT(unknown_area_beyond(*map, V(5.95, 0.9), V(1, 0), o), 0.05);
}

// A crossing traversed between two regions explains nothing of its other branches: the
// hallway's open end beside it stays a frontier; a traversed door's strip does not.
TEST(Frontiers, ACrossingsOutlineLeavesItsOtherBranchesOpen)
{
  auto map = hallway(false);
  const int64_t a = map->current_region;
  const int64_t b = add_region(map.get(), V(0, -3), V(6, -0.2), {}).id;   // south of the hallway, apart
  rgmap::Gateway& crossing = map->add_gateway(rgmap::GatewayClass::kXCrossing, a, kUtime);
  crossing.gateway_points = {V(5, 0), V(6.5, 0), V(6.5, 1.8), V(5, 1.8)};
  map->connect(crossing.id, b, Pose2(0, -3, 0));
  EXPECT_EQ(find_frontiers(*map, a, FrontierOptions{}).frontiers.size(), 1u) << "the east end stays open";
  crossing.gateway_points = {V(6, 0), V(6, 1.8)};   // a door in the east end instead
  EXPECT_TRUE(find_frontiers(*map, a, FrontierOptions{}).frontiers.empty());
}

GatewaySighting sighting(const V& at, double heading)
{
  GatewaySighting s;
  s.cls = rgmap::GatewayClass::kDoor;
  s.crossing = at;
  s.headings = {heading};
  s.observations = 5;
  return s;
}

// The closed hallway (the current region, where the robot started) and a room north of it
// ([0, 6] x [5, 7], the id returned), joined by a traversed door.
std::pair<std::shared_ptr<rgmap::RgMap>, int64_t> hallway_and_room()
{
  auto map = hallway(true);
  const int64_t room = add_region(map.get(), V(0, 5), V(6, 7), {}).id;
  rgmap::Gateway& g = map->add_gateway(rgmap::GatewayClass::kDoor, map->current_region, kUtime);
  map->connect(g.id, room, Pose2(0, 5, 0));
  return {map, room};
}

TEST(GatewayStack, BreadthFirstThenNearestAndDoneWhenPassed)
{
  const auto [map, r2] = hallway_and_room();
  const int64_t r1 = map->current_region;

  GatewayStack stack;
  stack.add(sighting(V(5, 6.5), M_PI / 2), r2, kUtime, *map);    // near the robot, one hop away
  stack.add(sighting(V(1, 1.8), M_PI / 2), r1, kUtime, *map);  // far, in the start region
  stack.add(sighting(V(1.2, 1.9), M_PI / 2 + 0.1), r1, kUtime, *map);   // the same gateway again
  stack.add(sighting(V(3, 1.8), -M_PI / 2), r1, kUtime, *map);  // heading back into known space: not stacked
  ASSERT_EQ(stack.entries().size(), 2u);
  const V robot(5, 5.5);
  auto order = stack.order(*map, r1, robot, kUtime);
  ASSERT_EQ(order.size(), 2u);
  EXPECT_EQ(order[0]->region_id, r1) << "breadth-first: the start region's gateway first";
  StackOptions nearest;
  nearest.breadth_first = false;
  GatewayStack by_distance(nearest);
  by_distance.from_json(stack.to_json());
  EXPECT_EQ(by_distance.order(*map, r1, robot, kUtime)[0]->region_id, r2);

  const int64_t far_id = order[0]->id;
  EXPECT_EQ(stack.update(V(1.1, 2.5), *map), 1) << "the robot past the gateway has traversed it";
  EXPECT_EQ(stack.entry(far_id)->state, StackEntry::State::kDone);

  // Failed: set aside until the retry time or a new region, for good after max attempts.
  const int64_t near_id = stack.order(*map, r1, robot, kUtime)[0]->id;
  stack.failed(near_id, "no path", kUtime, kUtime + 60 * kSecond, 2, 2, {});
  EXPECT_TRUE(stack.order(*map, r1, robot, kUtime + kSecond).empty());
  EXPECT_EQ(stack.order(*map, r1, robot, kUtime + 61 * kSecond).size(), 1u);
  stack.failed(near_id, "no path", kUtime + 60 * kSecond, kUtime + 120 * kSecond, 2, 2, {});
  EXPECT_TRUE(stack.order(*map, r1, robot, kUtime + 1000 * kSecond).empty());
  EXPECT_EQ(stack.entry(near_id)->reason, "no path");

  GatewayStack copy;
  copy.from_json(stack.to_json());
  EXPECT_EQ(copy.to_json(), stack.to_json());
  nlohmann::json bad = stack.to_json();
  bad["entries"][0]["state"] = "maybe";
  EXPECT_THROW(copy.from_json(bad), std::invalid_argument);
}

// The open region's freespace takes in all the laser saw from it, a crossing's branches the robot
// has not gone through too; it ends at the crossing once the region is finalised. Only the space
// of a region the robot has left says that what lies beyond a gateway was seen.
TEST(GatewayStack, SpaceOfTheOpenRegionIsNotSeenBeyond)
{
  auto map = hallway(false);
  const int64_t r1 = map->current_region;
  GatewayStack stack;
  stack.add(sighting(V(10, 0.9), 0.0), r1, kUtime, *map);   // east, past the hallway's open end
  ASSERT_EQ(stack.entries().size(), 1u);
  rgmap::Region& beyond = add_region(map.get(), V(6, 0), V(14, 1.8), {});   // open: the robot in it
  EXPECT_EQ(stack.update(V(3, 0.9), *map), 0) << "provisional space of the open region";
  beyond.state = rgmap::Region::State::kFinalised;
  EXPECT_EQ(stack.update(V(3, 0.9), *map), 1) << "the region left: seen beyond";
  EXPECT_EQ(stack.entries()[0].reason, "seen beyond");
}

// A gateway that failed and is due again waits behind every one never tried, however near the
// start it lies: else a gap the robot cannot pass, due again whenever the map grows, holds back
// the gateways seen since.
TEST(GatewayStack, FailedEntriesComeAfterUntriedOnes)
{
  const auto [map, r2] = hallway_and_room();
  const int64_t r1 = map->current_region;
  GatewayStack stack;
  stack.add(sighting(V(1, 1.8), M_PI / 2), r1, kUtime, *map);    // in the start region
  stack.add(sighting(V(5, 6.5), M_PI / 2), r2, kUtime, *map);    // one hop away
  const V robot(1, 1);
  auto order = stack.order(*map, r1, robot, kUtime);
  ASSERT_EQ(order.size(), 2u);
  const int64_t start_id = order[0]->id, far_id = order[1]->id;
  EXPECT_EQ(order[0]->region_id, r1);
  stack.failed(start_id, "no progress", kUtime, kUtime + 60 * kSecond, 3, 2, {});
  order = stack.order(*map, r1, robot, kUtime + 61 * kSecond);
  ASSERT_EQ(order.size(), 2u) << "due again";
  EXPECT_EQ(order[0]->id, far_id) << "the untried gateway first";
  EXPECT_EQ(order[1]->id, start_id);
}

// A robot turning through a crossing from one branch into another is past the crossing's middle
// along the branches it did not take, by as much as the detector's estimate of the middle is off:
// those stay on the stack until it stands past their goals; a door is through a step past its line.
TEST(GatewayStack, ACrossingsBranchIsTakenOnlyPastItsGoal)
{
  auto map = hallway(true);
  const int64_t r1 = map->current_region;
  GatewaySighting crossing = sighting(V(10, 0.9), 0.0);   // east, out of the hallway's known end
  crossing.cls = rgmap::GatewayClass::kXCrossing;
  crossing.headings = {0.0, M_PI / 2};                     // east and north
  GatewayStack stack;
  stack.add(crossing, r1, kUtime, *map);
  ASSERT_EQ(stack.entries().size(), 2u);
  // Turning from the west into the north branch, a little east of the middle.
  EXPECT_EQ(stack.update(V(10.5, 1.2), *map), 0) << "half a metre east of the middle is still the crossing";
  EXPECT_EQ(stack.update(V(10.5, 2.5), *map), 1) << "past the north goal: the north branch is taken";
  EXPECT_EQ(stack.entries()[1].state, StackEntry::State::kDone);
  EXPECT_EQ(stack.entries()[0].state, StackEntry::State::kPending) << "the east branch is still to be explored";

  GatewayStack doors;
  doors.add(sighting(V(10, 0.9), 0.0), r1, kUtime, *map);
  EXPECT_EQ(doors.update(V(10.5, 1.0), *map), 1) << "a step past a door's line is through it";
}

TEST(PlaceView, CountsFreeSpaceAndWallNearThePlace)
{
  const auto map = hallway(true);
  const PlaceViewOptions o;
  // 2 m round (3, 0.9): the hallway's free space is 1.8 m wide across, the walls pass at 0.9 m.
  const PlaceView v = view_of_place(*map, V(3, 0.9), o);
  EXPECT_NEAR(v.free_samples * o.sample_m * o.sample_m, 2 * (2 * std::sqrt(4 - 0.81) * 0.9), 0.6);
  EXPECT_NEAR(v.wall_m, 2 * 2 * std::sqrt(4 - 0.81), 0.01);
  EXPECT_FALSE(place_changed(v, view_of_place(*map, V(3, 0.9), o), o));
  EXPECT_FALSE(place_changed(PlaceView{}, v, o)) << "a place never looked at has not changed";
  EXPECT_EQ(view_of_place(*map, V(30, 30), o).free_samples, 0);
  EXPECT_EQ(place_view_from_json(place_view_json(v)).free_samples, v.free_samples);
  EXPECT_THROW(place_view_from_json(nlohmann::json::array({1})), std::invalid_argument);
}

// A hallway [0, 6] x [0, 2] with a 1 m door in its north wall at x in [2, 3]; the rest walled.
std::shared_ptr<rgmap::RgMap> hallway_with_a_door()
{
  auto map = std::make_shared<rgmap::RgMap>();
  const std::vector<Wall> walls = {{V(0, 0), V(6, 0)}, {V(0, 0), V(0, 2)}, {V(6, 0), V(6, 2)},
                                   {V(0, 2), V(2, 2)}, {V(3, 2), V(6, 2)}};
  map->current_region = add_region(map.get(), V(0, 0), V(6, 2), walls).id;
  map->version = 1;
  return map;
}

// The detector's crossing of a door seen from the hallway lies along the wall from it: the goal
// is aimed through the opening the lines show, with room for the robot; a crossing in the opening
// stays, and one with no opening near stays where it was seen.
TEST(Opening, AGoalIsAimedThroughTheOpeningBesideTheCrossing)
{
  const auto map = hallway_with_a_door();
  const OpeningOptions o;
  const double width = 0.62, depth = 1.4;
  const auto aimed_at = aim_through_opening(*map, V(3.6, 1.0), M_PI / 2, depth, width, o);
  ASSERT_TRUE(aimed_at);
  const V aimed = *aimed_at;
  EXPECT_GE(aimed.x(), 2.0 + 0.5 * width - 1e-9);
  EXPECT_LE(aimed.x(), 3.0 - 0.5 * width + 1e-9);
  EXPECT_NEAR(aimed.x(), 3.0 - 0.5 * width, 0.1) << "the nearest place with room, not the opening's middle";
  EXPECT_DOUBLE_EQ(aimed.y(), 1.0);
  EXPECT_EQ(aim_through_opening(*map, V(2.5, 1.0), M_PI / 2, depth, width, o), V(2.5, 1.0));
  EXPECT_FALSE(aim_through_opening(*map, V(5.0, 1.0), M_PI / 2, depth, width, o)) << "no opening within 1 m";
  EXPECT_FALSE(aim_through_opening(*map, V(2.5, 1.0), M_PI / 2, depth, 1.2, o)) << "an opening narrower than the lane";
  EXPECT_EQ(aim_through_opening(*map, V(10.0, 1.0), M_PI / 2, depth, width, o), V(10.0, 1.0)) << "no line near: as seen";
  OpeningOptions off;
  off.search_m = 0.0;
  EXPECT_EQ(aim_through_opening(*map, V(5.0, 1.0), M_PI / 2, depth, width, off), V(5.0, 1.0));

  // A desk 0.8 m inside the room, across the door: the opening is in the wall, not beyond.
  rgmap::LineSegment desk;
  desk.a = V(1.8, 2.8);
  desk.b = V(3.2, 2.8);
  map->region(map->current_region)->segments.push_back(desk);
  EXPECT_EQ(aim_through_opening(*map, V(2.5, 2.0), M_PI / 2, depth, width, o), V(2.5, 2.0));
  EXPECT_EQ(aim_through_opening(*map, V(2.5, 1.0), M_PI / 2, depth, width, o), V(2.5, 1.0));
}

// A gateway set aside for good comes back when the map near it changes — a fragment of wall
// across it dropped (a person who stood there walked on) — and not while nothing there changed.
TEST(GatewayStack, SetAsideForGoodIsTriedAgainOnceTheMapNearItChanged)
{
  auto map = hallway(true);
  const int64_t r1 = map->current_region;
  rgmap::Region& region = *map->region(r1);
  // Something standing across the hallway's east part: a short line that was not there before.
  rgmap::LineSegment person;
  person.a = V(4.8, 0.7);
  person.b = V(4.8, 1.1);
  region.segments.push_back(person);
  GatewayStack stack;
  stack.add(sighting(V(5, 0.9), 0.0), r1, kUtime, *map);
  ASSERT_EQ(stack.entries().size(), 1u);
  const int64_t id = stack.entries()[0].id;
  const PlaceViewOptions o;
  stack.failed(id, "no path", kUtime, kUtime + 60 * kSecond, 1, 1, view_of_place(*map, V(5, 0.9), o));
  const V robot(1, 0.9);
  EXPECT_TRUE(stack.order(*map, r1, robot, kUtime + 1000 * kSecond).empty()) << "for good after one attempt";
  EXPECT_EQ(stack.release_changed(*map, o, kUtime + 1000 * kSecond, 60 * kSecond, 1), 0) << "nothing changed near it";

  region.segments.pop_back();   // the person walked on
  EXPECT_EQ(stack.release_changed(*map, o, kUtime + 10 * kSecond, 60 * kSecond, 1), 0) << "too soon after it failed";
  EXPECT_EQ(stack.release_changed(*map, o, kUtime + 61 * kSecond, 60 * kSecond, 1), 1);
  EXPECT_EQ(stack.order(*map, r1, robot, kUtime + 61 * kSecond).size(), 1u);
  // Failing again on the same map: for good again, and released no more.
  stack.failed(id, "no path", kUtime + 70 * kSecond, kUtime + 130 * kSecond, 1, 1, view_of_place(*map, V(5, 0.9), o));
  EXPECT_EQ(stack.release_changed(*map, o, kUtime + 1000 * kSecond, 60 * kSecond, 1), 0);
  GatewayStack copy;
  copy.from_json(stack.to_json());
  EXPECT_EQ(copy.to_json(), stack.to_json());
}

// Options of the tests that follow the goals of exploring: no look behind first.
ExplorerOptions no_look()
{
  ExplorerOptions o;
  o.recovery.look_at_start = false;
  return o;
}

// The explorer's goals in the open hallway: its frontier, then (the frontier still there once
// the robot stood at it: the region's map ends there) through it as a gateway, then the end.
TEST(Explorer, FrontierThenThroughItThenDone)
{
  ExplorerOptions o = no_look();
  Explorer ex(o);
  int64_t t = kUtime;
  EXPECT_FALSE(ex.step(t).goal);
  EXPECT_EQ(ex.phase(), Phase::kWaiting);
  auto map = hallway(false);
  ex.set_map(map);
  ex.set_pose({t, Pose2(1, 0.9, 0)});
  Command c = ex.step(t);
  ASSERT_TRUE(c.goal);
  EXPECT_EQ(c.goal->kind, ExploreGoal::Kind::kFrontier);
  EXPECT_NEAR(c.goal->frontier_point.x(), 5.9, 0.1);
  // Looked at from a view point: clear of the unknown past the open end, within range, facing it.
  EXPECT_LT(c.goal->map_point.x(), 6.0 - o.robot_radius);
  EXPECT_GT(c.goal->map_point.x(), 6.0 - o.view.range_m);
  EXPECT_LT(std::abs(c.goal->heading), 0.5);
  EXPECT_DOUBLE_EQ(c.goal->heading_tolerance, o.view.heading_tolerance);
  EXPECT_FALSE(c.goal->beyond_known);

  ex.goal_report(c.goal->goal_id, GoalOutcome::kReached, "", t += kSecond);
  ex.set_pose({t, Pose2(c.goal->map_point, 0)});
  c = ex.step(t);
  ASSERT_TRUE(c.goal) << ex.status().activity;
  EXPECT_EQ(c.goal->kind, ExploreGoal::Kind::kGateway);
  EXPECT_TRUE(c.goal->beyond_known);
  EXPECT_GT(c.goal->map_point.x(), 6.5);
  EXPECT_EQ(ex.stack().count(StackEntry::State::kPending), 1);

  // Through: the robot past the opening; the map now knows what lies beyond.
  add_region(map.get(), V(6, 0), V(9, 1.8), {{V(6, 0), V(9, 0)}, {V(6, 1.8), V(9, 1.8)}, {V(9, 0), V(9, 1.8)}});
  map->current_region = 2;
  ex.set_pose({t += kSecond, Pose2(7, 0.9, 0)});
  c = ex.step(t);
  EXPECT_FALSE(c.goal);
  EXPECT_EQ(ex.phase(), Phase::kDone) << ex.status().activity;
  EXPECT_EQ(ex.stack().count(StackEntry::State::kDone), 1);
  const auto finished = ex.take_finished_regions();
  EXPECT_EQ(finished.size(), 2u);
  EXPECT_TRUE(ex.take_finished_regions().empty()) << "each region is offered for naming once";
}

// A door seen from the hallway, its crossing point half a metre along the wall from the opening
// (the opening's frontier is the stacked door's): the gateway goal goes through the opening.
TEST(Explorer, AGatewayGoalGoesThroughTheOpeningTheMapShows)
{
  Explorer ex(no_look());
  const int64_t t = kUtime;
  const auto map = hallway_with_a_door();
  ex.set_map(map);
  ex.set_pose({t, Pose2(1, 1, 0)});
  ex.add_sightings({sighting(V(3.2, 1.5), M_PI / 2)}, t);
  const Command c = ex.step(t);
  ASSERT_TRUE(c.goal) << ex.status().activity;
  ASSERT_EQ(c.goal->kind, ExploreGoal::Kind::kGateway);
  // Within the opening, the robot's body clear of both jambs.
  const double radius = ExplorerOptions{}.robot_radius;
  EXPECT_GT(c.goal->map_point.x(), 2.0 + radius);
  EXPECT_LT(c.goal->map_point.x(), 3.0 - radius) << "through the opening, not at the wall beside it";
  EXPECT_NEAR(c.goal->map_point.y(), 2.5, 1e-9);
}

// A door the detector saw where the map's lines show a wall with no opening the robot fits
// (a gap between furniture, a corner): set aside for good, and exploring ends instead of driving
// at the wall until the goal fails, over and over.
TEST(Explorer, AnEntryTheMapShowsNoOpeningForIsSetAside)
{
  Explorer ex(no_look());
  const int64_t t = kUtime;
  const auto map = hallway(true);
  ex.set_map(map);
  ex.set_pose({t, Pose2(1, 0.9, 0)});
  ex.add_sightings({sighting(V(3, 1.2), M_PI / 2)}, t);
  ASSERT_EQ(ex.stack().entries().size(), 1u);
  const Command c = ex.step(t);
  EXPECT_FALSE(c.goal) << c.goal->map_point.transpose();
  EXPECT_EQ(ex.stack().count(StackEntry::State::kSetAside), 1);
  EXPECT_EQ(ex.stack().entries()[0].reason.rfind("no opening", 0), 0u) << ex.stack().entries()[0].reason;
  EXPECT_EQ(ex.phase(), Phase::kDone) << ex.status().activity;
}

// Set aside for good, the entry is looked at again when the map near it changes; still with no
// opening, it is set aside again without a goal (the hallway's open end keeps exploring going).
TEST(Explorer, AnEntryWithNoOpeningStaysAsideWhenTheMapNearItChanges)
{
  Explorer ex(no_look());
  int64_t t = kUtime;
  const auto map = hallway(false);
  ex.set_map(map);
  ex.set_pose({t, Pose2(1, 0.9, 0)});
  ex.add_sightings({sighting(V(3, 1.2), M_PI / 2)}, t);
  Command c = ex.step(t);
  ASSERT_TRUE(c.goal);
  ASSERT_EQ(c.goal->kind, ExploreGoal::Kind::kFrontier);
  ASSERT_EQ(ex.stack().count(StackEntry::State::kSetAside), 1);
  ex.goal_report(c.goal->goal_id, GoalOutcome::kNoPath, "goal unreachable", t += kSecond);

  auto changed = std::make_shared<rgmap::RgMap>(*map);
  rgmap::LineSegment scrap;   // the map near the entry changes; still no opening
  scrap.a = V(2.2, 1.0);
  scrap.b = V(3.8, 1.0);
  changed->region(changed->current_region)->segments.push_back(scrap);
  ++changed->version;
  ex.set_map(changed);
  c = ex.step(t += static_cast<int64_t>(no_look().retry_after_s + 1) * kSecond);
  ASSERT_TRUE(c.goal) << ex.status().activity;
  EXPECT_NE(c.goal->kind, ExploreGoal::Kind::kGateway) << "no goal through a wall";
  EXPECT_EQ(ex.stack().entries()[0].retry_utime, 0) << "for good again";
  EXPECT_EQ(ex.stack().entries()[0].failed_utime, t) << "looked at again now";
}

// Every region entered before is complete before a new gateway (diss. ch. 7): the robot in a
// finished room off a hallway whose far end is still open goes back to that end before the
// room's other door, however the map's current region changed as it stood in the doorway.
TEST(Explorer, RegionsEnteredBeforeAreCompletedBeforeANewGateway)
{
  auto map = hallway(false);
  const int64_t hall = map->current_region;
  const int64_t room = add_region(map.get(), V(0, 1.8), V(3, 4),
                                  {{V(0, 1.8), V(0, 4)}, {V(3, 1.8), V(3, 4)}, {V(0, 4), V(1, 4)}, {V(2, 4), V(3, 4)}})
                           .id;
  rgmap::Gateway& door = map->add_gateway(rgmap::GatewayClass::kDoor, hall, kUtime);
  map->connect(door.id, room, Pose2(0, 1.8, 0));
  map->current_region = room;
  ExplorerOptions o = no_look();
  const auto explorer = [&](bool after_regions) {
    o.stack.after_regions = after_regions;
    auto ex = std::make_unique<Explorer>(o);
    ex->set_map(map);
    ex->set_pose({kUtime, Pose2(1.5, 3, 0)});
    ex->add_sightings({sighting(V(1.5, 4), M_PI / 2)}, kUtime);   // the room's other door, north
    return ex;
  };
  auto ex = explorer(true);
  Command c = ex->step(kUtime);
  ASSERT_TRUE(c.goal) << ex->status().activity;
  EXPECT_EQ(c.goal->kind, ExploreGoal::Kind::kRegion);
  EXPECT_EQ(c.goal->region_id, hall);
  EXPECT_NEAR(c.goal->frontier_point.x(), 5.9, 0.1);
  // Failed once: tried again after the stack, not before it (else the robot would go to and fro
  // between a frontier it cannot reach and the gateways it leaves waiting).
  ex->goal_report(c.goal->goal_id, GoalOutcome::kNoPath, "goal unreachable: no route", kUtime + kSecond);
  c = ex->step(kUtime + static_cast<int64_t>(o.retry_after_s + 2) * kSecond);   // due again by then
  ASSERT_TRUE(c.goal) << ex->status().activity;
  EXPECT_EQ(c.goal->kind, ExploreGoal::Kind::kGateway);

  c = explorer(false)->step(kUtime);
  ASSERT_TRUE(c.goal);
  EXPECT_EQ(c.goal->kind, ExploreGoal::Kind::kGateway) << "the stack first: the hallway waits";
}

// A frontier the robot could only look at from space it cannot drive to (past a gap narrower
// than its body) has no view point there: its goal is the frontier itself, any heading, left to
// the planner (which may know a way round), never a place past the gap.
TEST(Explorer, AFrontierSeenOnlyFromBeyondAGapTheRobotCannotPassHasNoViewPointThere)
{
  ExplorerOptions o = no_look();
  auto map = std::make_shared<rgmap::RgMap>();
  // A hallway [0, 9] x [0, 1.8] open at its east end, cut at x = 6 by a wall with a 0.3 m gap.
  map->current_region = add_region(map.get(), V(0, 0), V(9, 1.8),
                                   {{V(0, 0), V(9, 0)}, {V(0, 1.8), V(9, 1.8)}, {V(0, 0), V(0, 1.8)},
                                    {V(6, 0), V(6, 1.5)}})
                            .id;
  // The first goal of an explorer new to the map, the robot at the west end.
  const auto first_goal = [&](int64_t version) {
    map->version = version;
    Explorer ex(o);
    ex.set_map(map);
    ex.set_pose({kUtime, Pose2(1, 0.9, 0)});
    const Command c = ex.step(kUtime);
    EXPECT_TRUE(c.goal) << ex.status().activity;
    return c.goal.value_or(ExploreGoal{});
  };
  const ExploreGoal narrow = first_goal(1);
  EXPECT_NEAR(narrow.frontier_point.x(), 8.9, 0.1);
  EXPECT_LT((narrow.map_point - narrow.frontier_point).norm(), 1e-9) << "a view point past the gap";
  EXPECT_GE(narrow.heading_tolerance, M_PI);

  // The gap a door wide: the frontier is looked at from a view point past it.
  map->region(map->current_region)->segments.back().b = V(6, 0.6);
  const ExploreGoal wide = first_goal(2);
  EXPECT_GT(wide.map_point.x(), 7.0);
  EXPECT_GT((wide.map_point - wide.frontier_point).norm(), 0.1);
}

// A goal the robot gets no nearer to (held by something the map does not show) fails after
// progress_timeout_s, long before the goal's own timeout.
TEST(Explorer, AGoalWithoutProgressFails)
{
  ExplorerOptions o = no_look();
  o.progress_timeout_s = 20;
  Explorer ex(o);
  int64_t t = kUtime;
  ex.set_map(hallway(false));
  ex.set_pose({t, Pose2(1, 0.9, 0)});
  Command c = ex.step(t);
  ASSERT_TRUE(c.goal);
  for (int k = 0; k < 19; ++k) {
    ex.set_pose({t += kSecond, Pose2(1 + 0.01 * k, 0.9, 0)});
    ex.step(t);
  }
  EXPECT_EQ(ex.status().goals_failed, 0);
  ex.set_pose({t += 2 * kSecond, Pose2(1.2, 0.9, 0)});
  ex.step(t);
  EXPECT_EQ(ex.status().goals_failed, 1) << ex.status().activity;
}

// The explorer's goal after a step, recovery goals (a look, a step back) taken as done.
std::optional<ExploreGoal> next_goal(Explorer& ex, int64_t t, int* recoveries = nullptr)
{
  for (int k = 0; k < 10; ++k) {
    const Command c = ex.step(t);
    if (!c.goal) {
      if (ex.status().activity.find("changing the view") == std::string::npos) return std::nullopt;
      continue;   // a recovery is due at the next step
    }
    if (c.goal->kind != ExploreGoal::Kind::kLook && c.goal->kind != ExploreGoal::Kind::kStep) return c.goal;
    if (recoveries) ++*recoveries;
    ex.goal_report(c.goal->goal_id, GoalOutcome::kReached, "", t);
  }
  return std::nullopt;
}

// The robot in the open hallway at (x, 0.9) at `t`: its first goal, which the planner finds no
// path to.
void first_goal_fails(Explorer& ex, const std::shared_ptr<rgmap::RgMap>& map, int64_t t, double x)
{
  ex.set_map(map);
  ex.set_pose({t, Pose2(x, 0.9, 0)});
  const auto g = next_goal(ex, t);
  ASSERT_TRUE(g);
  ex.goal_report(g->goal_id, GoalOutcome::kNoPath, "blocked", t);
}

// Failed goals tried again after 30 s, at most `max_attempts` times; no look behind first.
ExplorerOptions retrying(int max_attempts)
{
  ExplorerOptions o = no_look();
  o.max_attempts = max_attempts;
  o.retry_after_s = 30;
  return o;
}

TEST(Explorer, ANoPathGoalIsTriedAgainLaterAndSetAsideAfterMaxAttempts)
{
  Explorer ex(retrying(2));
  int64_t t = kUtime;
  ASSERT_NO_FATAL_FAILURE(first_goal_fails(ex, hallway(false), t, 1.0));
  std::optional<ExploreGoal> g;
  // Nothing else left, and it failed from here: the robot looks behind (no track to step back
  // along yet), then waits.
  int recoveries = 0;
  EXPECT_FALSE(next_goal(ex, t += kSecond, &recoveries));
  EXPECT_EQ(recoveries, 1);
  EXPECT_EQ(ex.phase(), Phase::kExploring) << "not done while a retry is due: " << ex.status().activity;
  // Failing again from the same place on the same map is no new attempt: still not done.
  for (int k = 0; k < 3; ++k) {
    g = next_goal(ex, t += 31 * kSecond, &recoveries);
    ASSERT_TRUE(g) << "tried again after retry_after_s";
    ex.goal_report(g->goal_id, GoalOutcome::kNoPath, "blocked", t);
  }
  EXPECT_EQ(recoveries, 1) << "looked from here once";
  next_goal(ex, t += kSecond);
  EXPECT_EQ(ex.phase(), Phase::kExploring) << ex.status().activity;
  // From elsewhere it counts: the second attempt sets it aside for good.
  ex.set_pose({t, Pose2(2, 0.9, 0)});
  g = next_goal(ex, t += 31 * kSecond);
  ASSERT_TRUE(g);
  ex.goal_report(g->goal_id, GoalOutcome::kNoPath, "blocked", t);
  EXPECT_FALSE(next_goal(ex, t += 100 * kSecond));
  EXPECT_EQ(ex.phase(), Phase::kDone) << ex.status().activity;
  EXPECT_EQ(ex.status().goals_failed, 5);
}

// Two doors the robot cannot get through, tried one after the other from where it stands: each
// failure is the first of its own goal (with one record of the last failure for all goals, only
// the first door's counted, the second never ran out of attempts, and exploring never ended).
TEST(Explorer, AFailureOfOneGoalDoesNotDiscountAnothers)
{
  Explorer ex(retrying(1));
  int64_t t = kUtime;
  auto map = std::make_shared<rgmap::RgMap>();
  const std::vector<Wall> walls = {{V(0, 0), V(8, 0)},     {V(0, 0), V(0, 1.8)},     {V(8, 0), V(8, 1.8)},
                                   {V(0, 1.8), V(1.5, 1.8)}, {V(2.5, 1.8), V(5.5, 1.8)}, {V(6.5, 1.8), V(8, 1.8)}};
  map->current_region = add_region(map.get(), V(0, 0), V(8, 1.8), walls).id;
  map->version = 1;
  ex.set_map(map);
  ex.set_pose({t, Pose2(4, 0.9, 0)});
  ex.add_sightings({sighting(V(2, 1.8), M_PI / 2), sighting(V(6, 1.8), M_PI / 2)}, t);
  std::set<int64_t> tried;
  for (int k = 0; k < 2; ++k) {
    const auto g = next_goal(ex, t);
    ASSERT_TRUE(g && g->kind == ExploreGoal::Kind::kGateway) << ex.status().activity;
    tried.insert(g->entry_id);
    ex.goal_report(g->goal_id, GoalOutcome::kNoPath, "goal unreachable: the goal is behind a wall", t);
  }
  EXPECT_EQ(tried.size(), 2u);
  for (const StackEntry& e : ex.stack().entries()) EXPECT_EQ(e.attempts, 1) << "entry " << e.id;
  // A restarted explorer knows where each failed from; a state file saying otherwise is refused.
  Explorer again(retrying(1));
  again.restore(ex.save());
  for (const StackEntry& e : again.stack().entries()) {
    ASSERT_TRUE(e.failed_from) << "entry " << e.id;
    EXPECT_NEAR(e.failed_from->robot.x(), 4.0, 1e-9);
    EXPECT_EQ(e.failed_from->map_version, 1);
  }
  nlohmann::json bad = ex.save();
  bad["stack"]["entries"][0]["failed_from"] = {4.0, 0.9};
  EXPECT_THROW(again.restore(bad), std::invalid_argument);
  // Both out of attempts: nothing left to wait for.
  EXPECT_FALSE(next_goal(ex, t += kSecond));
  EXPECT_EQ(ex.phase(), Phase::kDone) << ex.status().activity;
}

// A frontier of the current region that failed waits behind the stack: tried again before it, a
// frontier the robot cannot get at (behind furniture) held it in one room while the rest of the
// building waited.
// The open hallway with a door seen in its north wall, the robot at its west end at `t`: the
// first goal, the hallway's open end, fails (no path) and is due again after retry_after_s.
std::shared_ptr<rgmap::RgMap> open_end_fails_beside_a_door(Explorer& ex, int64_t t)
{
  auto map = hallway(false, 3.0);
  ex.set_map(map);
  ex.set_pose({t, Pose2(1, 0.9, 0)});
  ex.add_sightings({sighting(V(3, 1.8), M_PI / 2)}, t);
  const auto g = next_goal(ex, t);
  EXPECT_TRUE(g && g->kind == ExploreGoal::Kind::kFrontier) << "the region first: " << ex.status().activity;
  if (g) ex.goal_report(g->goal_id, GoalOutcome::kNoPath, "goal unreachable", t);
  return map;
}

TEST(Explorer, AFailedFrontierOfTheCurrentRegionWaitsBehindTheStack)
{
  Explorer ex(retrying(3));
  int64_t t = kUtime;
  const auto map = open_end_fails_beside_a_door(ex, t);
  ex.set_pose({t += kSecond, Pose2(1.5, 0.9, 0)});
  auto g = next_goal(ex, t += 31 * kSecond);   // the frontier is due again by now
  ASSERT_TRUE(g) << ex.status().activity;
  EXPECT_EQ(g->kind, ExploreGoal::Kind::kGateway);
  // The stack empty (the door gone through and seen beyond), the frontier is tried again.
  ex.goal_report(g->goal_id, GoalOutcome::kReached, "", t);
  add_region(map.get(), V(2, 1.8), V(4, 4), {{V(2, 1.8), V(2, 4)}, {V(4, 1.8), V(4, 4)}, {V(2, 4), V(4, 4)}});
  ++map->version;
  ex.set_map(map);
  g = next_goal(ex, t += kSecond);
  ASSERT_TRUE(g) << ex.status().activity;
  EXPECT_EQ(g->kind, ExploreGoal::Kind::kFrontier);
  EXPECT_NEAR(g->frontier_point.x(), 5.9, 0.1);
}

// A frontier goal under way is not dropped for the stack's next gateway: one tried again while
// nothing on the stack was due was dropped half-way whenever an entry came due, and tried again
// after it, over and over.
TEST(Explorer, AFrontierGoalUnderWayIsNotDroppedForTheStack)
{
  Explorer ex(retrying(3));
  int64_t t = kUtime;
  open_end_fails_beside_a_door(ex, t);   // due again at +30 s
  ex.set_pose({t += kSecond, Pose2(1.5, 0.9, 0)});
  auto g = next_goal(ex, t += 9 * kSecond);
  ASSERT_TRUE(g);
  ASSERT_EQ(g->kind, ExploreGoal::Kind::kGateway);
  ex.goal_report(g->goal_id, GoalOutcome::kNoPath, "goal unreachable", t);   // due again at +40 s
  ex.set_pose({t += kSecond, Pose2(2, 0.9, 0)});
  g = next_goal(ex, t += 21 * kSecond);   // +32 s: only the frontier is due
  ASSERT_TRUE(g) << ex.status().activity;
  ASSERT_EQ(g->kind, ExploreGoal::Kind::kFrontier);
  const Command c = ex.step(t += 10 * kSecond);   // +42 s: the door is due too
  EXPECT_FALSE(c.goal) << "replaced by " << (c.goal ? to_string(c.goal->kind) : "");
  ASSERT_TRUE(ex.goal());
  EXPECT_EQ(ex.goal()->goal_id, g->goal_id);
}

// A robot held where it stands (wedged among furniture, its collision avoidance finding no way
// on) fails every goal by the progress bound. Those failures are not the goals' fault until the
// robot arrived somewhere since the last one: exploring does not end while the robot cannot move.
TEST(Explorer, ARobotThatCannotGetOnIsNotDone)
{
  ExplorerOptions o = retrying(1);
  o.progress_timeout_s = 20;
  Explorer ex(o);
  int64_t t = kUtime;
  auto map = hallway(false);
  // The goal ends after 21 s with the robot where it was; the map changes meanwhile (people).
  const auto fail_by_no_progress = [&](const ExploreGoal& g) {
    for (int k = 0; k < 21; ++k) {
      auto changed = std::make_shared<rgmap::RgMap>(*map);
      changed->version = map->version + k + 1;
      ex.set_map(changed);
      ex.set_pose({t += kSecond, Pose2(1, 0.9, 0)});
      ex.step(t);
    }
    map->version += 22;
    EXPECT_FALSE(ex.goal() && ex.goal()->goal_id == g.goal_id) << "still running: " << ex.status().activity;
  };
  ex.set_map(map);
  ex.set_pose({t, Pose2(1, 0.9, 0)});
  for (int k = 0; k < 4; ++k) {
    const auto g = next_goal(ex, t += 31 * kSecond);
    ASSERT_TRUE(g) << "try " << k << ": " << ex.status().activity;
    fail_by_no_progress(*g);
    EXPECT_NE(ex.phase(), Phase::kDone) << ex.status().activity;
  }
  EXPECT_EQ(ex.status().goals_failed, 4);
  // Once the robot arrived somewhere (here at the frontier's view point: the open end, still open,
  // goes to the stack), the next failure is the goal's: set aside for good, exploring ends.
  auto g = next_goal(ex, t += 31 * kSecond);
  ASSERT_TRUE(g);
  ex.goal_report(g->goal_id, GoalOutcome::kReached, "", t);
  g = next_goal(ex, t += kSecond);
  ASSERT_TRUE(g) << ex.status().activity;
  EXPECT_EQ(g->kind, ExploreGoal::Kind::kGateway);
  fail_by_no_progress(*g);
  next_goal(ex, t += 100 * kSecond);
  EXPECT_EQ(ex.phase(), Phase::kDone) << ex.status().activity;
}

// A frontier set aside for good is tried once more when the map near it changes (here a short
// line appears 1 m from it: a person stepping in), and exploring ends only once it failed again
// on that map.
TEST(Explorer, AFrontierSetAsideForGoodIsTriedAgainWhenTheMapNearItChanges)
{
  // (Set aside for good with nothing changed near it, exploring ends: the test above.)
  Explorer again(retrying(1));
  int64_t t = kUtime;
  const auto map = hallway(false);
  ASSERT_NO_FATAL_FAILURE(first_goal_fails(again, map, t, 2.0));
  auto changed = std::make_shared<rgmap::RgMap>(*map);
  rgmap::LineSegment person;
  person.a = V(4.9, 0.7);
  person.b = V(4.9, 1.1);
  changed->region(changed->current_region)->segments.push_back(person);
  ++changed->version;
  again.set_map(changed);
  again.set_pose({t, Pose2(2.5, 0.9, 0)});
  const auto g = next_goal(again, t += 31 * kSecond);
  ASSERT_TRUE(g) << "the map near it changed: tried again (" << again.status().activity << ")";
  again.goal_report(g->goal_id, GoalOutcome::kNoPath, "blocked", t);
  again.set_pose({t, Pose2(3, 0.9, 0)});
  EXPECT_FALSE(next_goal(again, t += 100 * kSecond));
  EXPECT_EQ(again.phase(), Phase::kDone) << again.status().activity;
}

// What the robot saw lies ahead of it: before it chooses, it turns to look behind (a goal where
// it stands, heading away from where it looked, with a heading tolerance); then it explores.
TEST(Explorer, LooksBehindFirst)
{
  Explorer ex;
  int64_t t = kUtime;
  ex.set_map(hallway(false));
  ex.set_pose({t, Pose2(1, 0.9, 0.4)});
  Command c = ex.step(t);
  ASSERT_TRUE(c.goal);
  EXPECT_EQ(c.goal->kind, ExploreGoal::Kind::kLook);
  EXPECT_LT((c.goal->region_point - V(1, 0.9)).norm(), 1e-9);
  EXPECT_NEAR(std::abs(geometry::normalize_angle(c.goal->heading - 0.4)), M_PI, 1e-9);
  EXPECT_LT(c.goal->heading_tolerance, M_PI);
  // Standing at its goal's place from the start does not end a look: the planner's REACHED does.
  c = ex.step(t += 2 * kSecond);
  EXPECT_FALSE(c.goal);
  ex.goal_report(ex.goal()->goal_id, GoalOutcome::kReached, "", t += kSecond);
  c = ex.step(t);
  ASSERT_TRUE(c.goal);
  EXPECT_EQ(c.goal->kind, ExploreGoal::Kind::kFrontier);
}

// The planner finds the robot's own place cut off (NO_PATH "start cut off: ..."): not the goal's
// fault, and standing there nothing changes. The robot looks behind; still cut off there, it
// steps back along its track; cut off at the same place after both, the goal fails as any other.
// Elsewhere it may look again.
TEST(Explorer, ACutOffPlaceIsLookedRoundAndSteppedAwayFrom)
{
  ExplorerOptions o = no_look();
  Explorer ex(o);
  int64_t t = kUtime;
  ex.set_map(hallway(false));
  for (double x = 1.0; x <= 3.0; x += 0.1) ex.set_pose({t += kSecond / 10, Pose2(x, 0.9, 0)});
  const std::string cut_off = "start cut off: no route from region 1 to region 1: the robot stands apart";
  auto fail_next = [&](const std::string& reason) {
    const Command c = ex.step(t += kSecond);
    EXPECT_TRUE(c.goal) << ex.status().activity;
    if (!c.goal) return ExploreGoal{};
    ex.goal_report(c.goal->goal_id, GoalOutcome::kNoPath, reason, t);
    return *c.goal;
  };
  EXPECT_EQ(fail_next(cut_off).kind, ExploreGoal::Kind::kFrontier);
  Command c = ex.step(t += kSecond);
  ASSERT_TRUE(c.goal);
  EXPECT_EQ(c.goal->kind, ExploreGoal::Kind::kLook);
  ex.goal_report(c.goal->goal_id, GoalOutcome::kReached, "", t);
  EXPECT_EQ(fail_next(cut_off).kind, ExploreGoal::Kind::kFrontier) << "the frontier is no failed place";
  c = ex.step(t += kSecond);
  ASSERT_TRUE(c.goal);
  EXPECT_EQ(c.goal->kind, ExploreGoal::Kind::kStep);
  // The newest place on the track at least step_m away (the track keeps one every 0.2 m).
  EXPECT_GE((c.goal->map_point - V(3.0, 0.9)).norm(), o.recovery.step_m - 0.11) << "back along the track";
  EXPECT_LT((c.goal->map_point - V(3.0, 0.9)).norm(), o.recovery.step_m + 0.3) << "back along the track";
  EXPECT_LT(c.goal->map_point.x(), 3.0);
  // The step not taken (the planner finds no way either): the frontier once more, then as any failure.
  ex.goal_report(c.goal->goal_id, GoalOutcome::kNoPath, cut_off, t);
  EXPECT_EQ(fail_next(cut_off).kind, ExploreGoal::Kind::kFrontier);
  c = ex.step(t += kSecond);
  EXPECT_FALSE(c.goal) << "waiting to try again: " << ex.status().activity;
  EXPECT_EQ(ex.phase(), Phase::kExploring);
  // Somewhere else, cut off again: a look first.
  ex.set_pose({t, Pose2(2.0, 0.9, 0)});
  c = ex.step(t += static_cast<int64_t>(o.retry_after_s * 1e6) + kSecond);
  ASSERT_TRUE(c.goal);
  ex.goal_report(c.goal->goal_id, GoalOutcome::kNoPath, cut_off, t);
  c = ex.step(t += kSecond);
  ASSERT_TRUE(c.goal);
  EXPECT_EQ(c.goal->kind, ExploreGoal::Kind::kLook);
}

// A frontier the map already knows the far side of (the next region's freespace begins a
// strip narrower than a robot farther on) offers nothing to look at: no goal, and with nothing
// else the explorer is done. With every frontier a goal (min_m2 0) it drives there.
TEST(Explorer, AFrontierWithLittleUnknownBeyondIsNoGoal)
{
  for (const double min_gain : {0.25, 0.0}) {
    ExplorerOptions o = no_look();
    o.frontier.gain.min_m2 = min_gain;
    Explorer ex(o);
    auto map = hallway(false);
    add_region(map.get(), V(6.2, 0), V(9, 1.8), {{V(6.2, 0), V(9, 0)}, {V(6.2, 1.8), V(9, 1.8)}, {V(9, 0), V(9, 1.8)}});
    const int64_t first = map->regions().begin()->first;
    ASSERT_EQ(find_frontiers(*map, first, o.frontier).frontiers.size(), 1u) << "the 0.2 m strip is unexplained";
    ex.set_map(map);
    ex.set_pose({kUtime, Pose2(1, 0.9, 0)});
    const auto g = next_goal(ex, kUtime);
    if (min_gain > 0) {
      EXPECT_FALSE(g) << "goal at (" << g->map_point.transpose() << ")";
      EXPECT_EQ(ex.phase(), Phase::kDone) << ex.status().activity;
    } else {
      ASSERT_TRUE(g);
      EXPECT_EQ(g->kind, ExploreGoal::Kind::kFrontier);
    }
  }
}

// The same frontier under the rule for regions the robot is not in (left_min_m2): a goal while
// the robot is in its region, none once it stands in a closed room north of it (going back costs
// a trip, and a look past it shows nothing).
TEST(Explorer, ALeftRegionsFrontierWithLittleUnknownBeyondIsNoGoal)
{
  ExplorerOptions o = no_look();
  o.frontier.gain.left_min_m2 = 0.25;
  for (const bool in_hallway : {true, false}) {
    Explorer ex(o);
    auto map = hallway(false);
    add_region(map.get(), V(6.2, 0), V(9, 1.8), {{V(6.2, 0), V(9, 0)}, {V(6.2, 1.8), V(9, 1.8)}, {V(9, 0), V(9, 1.8)}});
    const int64_t room =
        add_region(map.get(), V(0, 5), V(6, 7), {{V(0, 5), V(6, 5)}, {V(0, 7), V(6, 7)}, {V(0, 5), V(0, 7)}, {V(6, 5), V(6, 7)}}).id;
    if (!in_hallway) map->current_region = room;
    ex.set_map(map);
    ex.set_pose({kUtime, in_hallway ? Pose2(1.0, 0.9, 0) : Pose2(3.0, 6.0, 0)});
    const auto g = next_goal(ex, kUtime);
    if (in_hallway) {
      ASSERT_TRUE(g) << ex.status().activity;
      EXPECT_EQ(g->kind, ExploreGoal::Kind::kFrontier);
    } else {
      EXPECT_FALSE(g) << "goal " << to_string(g->kind) << " in region " << g->region_id << " at (" << g->map_point.transpose() << ")";
      EXPECT_EQ(ex.phase(), Phase::kDone) << ex.status().activity;
    }
  }
}

// A gateway gone through claims its opening only while a look past it would show nothing: the
// robot went a metre through a junction's branch at the hallway's open end, and the hallway
// still ends in the unknown there (its map took nothing in): the end is a frontier again. Without
// the gain rule (min_m2 0) the entry gone through claims it, and exploring ends.
TEST(Explorer, AFrontierAtAGatewayGoneThroughIsAGoalWhileThereIsSomethingToSee)
{
  for (const double min_gain : {0.25, 0.0}) {
    ExplorerOptions o = no_look();
    o.frontier.gain.min_m2 = min_gain;
    Explorer ex(o);
    const int64_t t = kUtime;
    ex.set_map(hallway(false));
    ex.add_sightings({sighting(V(5.8, 0.9), 0.0)}, t);
    ex.set_pose({t, Pose2(6.3, 0.9, 0)});   // 0.5 m through it
    const Command c = ex.step(t);
    EXPECT_EQ(ex.stack().count(StackEntry::State::kDone), 1);
    if (min_gain > 0) {
      ASSERT_TRUE(c.goal) << ex.status().activity;
      EXPECT_EQ(c.goal->kind, ExploreGoal::Kind::kFrontier);
      EXPECT_NEAR(c.goal->frontier_point.x(), 5.9, 0.1);
    } else {
      EXPECT_FALSE(c.goal);
      EXPECT_EQ(ex.phase(), Phase::kDone) << ex.status().activity;
    }
  }
}

// Only a gateway the planner took for closed for a while is in the way: the goal is due again
// later and counts no attempt; each such failure waits twice as long as the one before, and
// max_closed_retries of them set it aside for good (a door shut for good is not tried for ever).
// One attempt before a goal is set aside, a retry after 10 s, `max_closed_retries`; no look behind first.
ExplorerOptions closed_retrying(int max_closed_retries)
{
  ExplorerOptions o = no_look();
  o.max_attempts = 1;
  o.retry_after_s = 10;
  o.max_closed_retries = max_closed_retries;
  return o;
}

TEST(Explorer, AGoalBehindAClosedGatewayWaitsLongerEachTimeAndIsSetAsideAfterMaxClosedRetries)
{
  Explorer ex(closed_retrying(3));
  int64_t t = kUtime;
  auto map = hallway(false);
  ex.set_map(map);
  const std::string closed = "behind a closed gateway: no route (closed gateways: 4)";
  ex.set_pose({t, Pose2(1, 0.9, 0)});
  Command c = ex.step(t);
  ASSERT_TRUE(c.goal);
  ex.goal_report(c.goal->goal_id, GoalOutcome::kNoPath, closed, t);
  // The k-th such failure waits 10 * 2^(k-1) s (from elsewhere each time: any other failure would count).
  double x = 1;
  for (const int wait_s : {10, 20}) {
    const int64_t failed = t;
    ex.set_pose({failed, Pose2(x += 0.6, 0.9, 0)});
    EXPECT_FALSE(ex.step(failed + (wait_s - 1) * kSecond).goal) << "due only after " << wait_s << " s";
    EXPECT_EQ(ex.phase(), Phase::kExploring) << ex.status().activity;
    c = ex.step(t = failed + (wait_s + 1) * kSecond);
    ASSERT_TRUE(c.goal) << "due again after " << wait_s << " s: " << ex.status().activity;
    ex.goal_report(c.goal->goal_id, GoalOutcome::kNoPath, closed, t);
  }
  // The third: set aside for good, nothing else left: the end.
  ex.set_pose({t, Pose2(x += 0.6, 0.9, 0)});
  EXPECT_FALSE(next_goal(ex, t += 1000 * kSecond));
  EXPECT_EQ(ex.phase(), Phase::kDone) << ex.status().activity;
}

// A goal behind a closed gateway counts no attempt: failing for another cause from elsewhere
// still sets it aside (max_attempts 1).
TEST(Explorer, AGoalBehindAClosedGatewayIsNoFailedAttempt)
{
  Explorer ex(closed_retrying(10));
  int64_t t = kUtime;
  auto map = hallway(false);
  ex.set_map(map);
  for (int k = 0; k < 4; ++k) {
    ex.set_pose({t, Pose2(1 + 0.6 * k, 0.9, 0)});   // from elsewhere each time: each would count
    ++map->version;
    const Command c = ex.step(t += (10 << k) * kSecond + kSecond);   // the k-th waited 10 * 2^(k-1) s
    ASSERT_TRUE(c.goal) << k << ": " << ex.status().activity;
    ex.goal_report(c.goal->goal_id, GoalOutcome::kNoPath, "behind a closed gateway: no route (closed gateways: 4)", t);
  }
  EXPECT_EQ(ex.phase(), Phase::kExploring);
  // The same from yet another place with another cause sets it aside (max_attempts 1): the end.
  ex.set_pose({t, Pose2(4, 0.9, 0)});
  ++map->version;
  const Command c = ex.step(t += 81 * kSecond);
  ASSERT_TRUE(c.goal);
  ex.goal_report(c.goal->goal_id, GoalOutcome::kNoPath, "goal unreachable: the goal is blocked in region 1", t);
  ex.step(t += 100 * kSecond);
  EXPECT_EQ(ex.phase(), Phase::kDone) << ex.status().activity;
}

TEST(Explorer, ARestartedExplorerGoesOnWhereItWas)
{
  Explorer ex(no_look());
  int64_t t = kUtime;
  auto map = hallway(false);
  ex.set_map(map);
  ex.set_pose({t, Pose2(1, 0.9, 0)});
  Command c = ex.step(t);
  ASSERT_TRUE(c.goal);
  ex.goal_report(c.goal->goal_id, GoalOutcome::kReached, "", t);
  ex.set_pose({t, Pose2(5.5, 0.9, 0)});
  c = ex.step(t += kSecond);
  ASSERT_TRUE(c.goal);
  const nlohmann::json saved = ex.save();

  Explorer again(no_look());
  again.restore(saved);
  again.set_map(map);
  again.set_pose({t, Pose2(5.5, 0.9, 0)});
  const Command d = again.step(t += kSecond);
  ASSERT_TRUE(d.goal);
  EXPECT_EQ(d.goal->kind, ExploreGoal::Kind::kGateway) << "the visited frontier is remembered";
  EXPECT_GT(d.goal->goal_id, c.goal->goal_id) << "goal ids go on rising";
  EXPECT_EQ(again.stack().entries().size(), ex.stack().entries().size());

  nlohmann::json bad = saved;
  bad["visited"] = {{1.0}};
  Explorer broken;
  EXPECT_THROW(broken.restore(bad), std::invalid_argument);
}

}  // namespace
}  // namespace rgnav::explorer
