// The planner's algorithm library (procs/planner) on small hand-made RG maps: region grids and
// framed-quadtree paths (length, clearance, narrow gaps), the RG-graph search with closed and
// learned gateways, targets, and the execution of a goal with a robot that follows the targets.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <queue>

#include "planner/edge_costs.h"
#include "planner/framed_quadtree.h"
#include "planner/global_planner.h"
#include "planner/no_path_reason.h"
#include "planner/planner.h"
#include "planner/region_grid.h"
#include "planner/region_planner.h"
#include "planner/route.h"
#include "planner/route_time.h"
#include "box_region.h"

namespace rgnav::planner {
namespace {

using Eigen::Vector2d;
using geometry::Pose2;
using V = Vector2d;
using Wall = std::pair<V, V>;

constexpr int64_t kUtime = 1'700'000'000'000'000;

// A region in the map frame offset by `lo`: walls (map frame) as its line map, and freespace
// at 0.1 m over the box [lo, hi] (map frame), less what `blocked` says.
rgmap::Region& add_region(rgmap::RgMap* map, const std::string& name, const V& lo, const V& hi,
                          const std::vector<Wall>& walls, std::function<bool(const V&)> blocked = {})
{
  rgmap::Region& r = testing::add_box_region(map, lo, hi, walls, 0.1, kUtime, blocked);
  r.name = name;
  r.state = rgmap::Region::State::kFinalised;
  return r;
}

// A gateway between two regions of the map at map point c (both region frames are offsets).
rgmap::Gateway& add_gateway(rgmap::RgMap* map, rgmap::GatewayClass cls, int64_t a, int64_t b, const V& c)
{
  rgmap::Gateway& g = map->add_gateway(cls, a, kUtime);
  const Pose2 map_from_a = map->region(a)->map_from_region, map_from_b = map->region(b)->map_from_region;
  g.crossing_points = {map_from_a.inverse() * c};
  g.gateway_points = g.crossing_points;
  map->connect(g.id, b, map_from_a.inverse() * map_from_b);
  return g;
}

// One room [0, 8] x [0, 5] with a wall from the bottom to y = 3.5 at x = 4.
rgmap::RgMap one_room_with_wall()
{
  rgmap::RgMap map;
  add_region(&map, "room", V(0, 0), V(8, 5),
             {{V(0, 0), V(8, 0)}, {V(8, 0), V(8, 5)}, {V(8, 5), V(0, 5)}, {V(0, 5), V(0, 0)}, {V(4, 0), V(4, 3.5)}});
  return map;
}

// Three regions: A [0,4]x[0,3] and B [5,9]x[0,3] joined by a door at (4.5, 1.5) through a 1 m
// wall gap; a hallway H [0,9]x[-2.5,-0.5]... joined to A and B by openings in their floors.
struct Ring
{
  rgmap::RgMap map;
  int64_t a = 0, b = 0, h = 0, door = 0, ha = 0, hb = 0;
};

// trimmed_door: neither region's freespace covers the door's opening (the RG kernel trims
// freespace at narrow passages); the gateway's points are its jambs.
Ring ring(bool trimmed_door = false)
{
  Ring r;
  const std::vector<Wall> walls_a = {{V(0, 0), V(1, 0)}, {V(2.2, 0), V(4, 0)}, {V(4, 0), V(4, 1)}, {V(4, 2), V(4, 3)},
                                     {V(4, 3), V(0, 3)}, {V(0, 3), V(0, 0)}};
  const std::vector<Wall> walls_door = {{V(4, 1), V(5, 1)}, {V(4, 2), V(5, 2)}};
  const std::vector<Wall> walls_b = {{V(5, 0), V(6.8, 0)}, {V(8, 0), V(9, 0)}, {V(9, 0), V(9, 3)}, {V(9, 3), V(5, 3)},
                                     {V(5, 3), V(5, 2)}, {V(5, 1), V(5, 0)}};
  const std::vector<Wall> walls_h = {{V(0, -2), V(9, -2)}, {V(9, -2), V(9, 0)}, {V(0, 0), V(0, -2)},
                                     {V(0, 0), V(1, 0)}, {V(2.2, 0), V(6.8, 0)}, {V(8, 0), V(9, 0)}};
  std::vector<Wall> a_lines = walls_a, b_lines = walls_b;
  a_lines.insert(a_lines.end(), walls_door.begin(), walls_door.end());
  r.a = add_region(&r.map, "Room A", V(0, 0), V(5, 3), a_lines,
                   [=](const V& c) { return c.x() > 4 && (trimmed_door || c.y() < 1 || c.y() > 2); }).id;
  r.b = add_region(&r.map, "Room B", V(4.5, 0), V(9, 3), b_lines,
                   [=](const V& c) { return c.x() < 5 && (trimmed_door || c.y() < 1 || c.y() > 2); }).id;
  r.h = add_region(&r.map, "hallway", V(0, -2), V(9, 0.5), walls_h,
                   [](const V& c) { return c.y() > 0 && !((c.x() > 1 && c.x() < 2.2) || (c.x() > 6.8 && c.x() < 8)); }).id;
  auto& door = add_gateway(&r.map, rgmap::GatewayClass::kDoor, r.a, r.b, V(4.5, 1.5));
  door.gateway_points = {V(4.5, 1.0), V(4.5, 2.0)};
  r.door = door.id;
  r.ha = add_gateway(&r.map, rgmap::GatewayClass::kOpening, r.h, r.a, V(1.6, 0)).id;
  r.hb = add_gateway(&r.map, rgmap::GatewayClass::kOpening, r.h, r.b, V(7.4, 0)).id;
  r.map.version = 1;
  return r;
}

PlannerOptions options()
{
  PlannerOptions o;
  o.grid.robot_radius = 0.26;
  return o;
}

TEST(RegionGrid, BlocksNearWallsAndUnknown)
{
  const auto map = one_room_with_wall();
  const RegionGrid grid(map.regions().begin()->second, options().grid);
  EXPECT_TRUE(grid.free(grid.cell_of(V(2, 2))));
  EXPECT_FALSE(grid.free(grid.cell_of(V(4.1, 1))));     // beside the inner wall
  EXPECT_FALSE(grid.free(grid.cell_of(V(0.1, 2))));     // beside the outer wall
  EXPECT_FALSE(grid.free(grid.cell_of(V(9, 2))));       // outside: unknown
  EXPECT_NEAR(grid.clearance(grid.cell_of(V(2, 2))), 2.0, 1.5 * grid.resolution());
  EXPECT_EQ(grid.level(grid.cell_of(V(2, 2))), 0);      // open space costs nothing extra
  EXPECT_GT(grid.level(grid.cell_of(V(0.35, 2))), 0);   // near a wall it does
}

// A blocked place in the only way between the room's halves cuts its free space in two: no
// way between them, but a robot on either side stands in the region's space, not apart from it
// (a robot held before a place was "cut off", and its goals got the wrong cause).
TEST(RegionPlanner, ABlockedPlaceCutsTheWayButNobodyOff)
{
  const auto map = one_room_with_wall();
  GridOptions o = options().grid;
  o.blocked_radius = 0.25;
  const RegionPlanner rp(map.regions().begin()->second, o, {}, {}, {V(4, 4.3)});
  EXPECT_FALSE(rp.plan(V(2, 1), V(6, 1), nullptr));
  const auto& g = rp.grid();
  EXPECT_NE(g.component(g.cell_of(V(2, 1))), g.component(g.cell_of(V(6, 1))));
  EXPECT_FALSE(rp.cut_off(V(2, 1)));
  EXPECT_FALSE(rp.cut_off(V(6, 1)));
  // A scrap the map itself cuts off stays cut off: outside the room.
  EXPECT_TRUE(rp.cut_off(V(9.5, 1)));
}

TEST(RegionPlanner, GoesAroundTheWallWithClearance)
{
  const auto map = one_room_with_wall();
  const RegionPlanner rp(map.regions().begin()->second, options().grid);
  std::string why;
  const auto path = rp.plan(V(2, 1), V(6, 1), &why);
  ASSERT_TRUE(path) << why;
  // Around the wall's end at (4, 3.5): the shortest way with the radius is ~ 2 * |(2,1)-(4,3.76)|.
  const double shortest = 2 * (V(4, 3.5 + 0.26) - V(2, 1)).norm();
  EXPECT_GT(path->length, shortest - 0.05);
  EXPECT_LT(path->length, shortest * 1.12);
  EXPECT_GE(path->min_clearance, 0.26);
  // Smoothing leaves few waypoints, not a staircase of cells.
  EXPECT_LE(path->points.size(), 8u);
  for (size_t i = 0; i + 1 < path->points.size(); ++i)
    EXPECT_TRUE(rp.grid().line_cost(path->points[i], path->points[i + 1]).has_value());
}

TEST(RegionPlanner, StraightInOpenSpace)
{
  const auto map = one_room_with_wall();
  const RegionPlanner rp(map.regions().begin()->second, options().grid);
  const auto path = rp.plan(V(1, 4), V(7, 4.2));
  ASSERT_TRUE(path);
  EXPECT_NEAR(path->length, (V(7, 4.2) - V(1, 4)).norm(), 0.05);
}

TEST(RegionPlanner, NoWayThroughAGapNarrowerThanTheRobot)
{
  rgmap::RgMap map;
  // A wall across the room with a 0.4 m gap: the robot (0.52 m wide) does not fit.
  add_region(&map, "room", V(0, 0), V(8, 5),
             {{V(0, 0), V(8, 0)}, {V(8, 0), V(8, 5)}, {V(8, 5), V(0, 5)}, {V(0, 5), V(0, 0)}, {V(4, 0), V(4, 2.3)},
              {V(4, 2.7), V(4, 5)}});
  const RegionPlanner rp(map.regions().begin()->second, options().grid);
  std::string why;
  EXPECT_FALSE(rp.plan(V(2, 2.5), V(6, 2.5), &why));
  EXPECT_EQ(why, "no way inside the region");
}

TEST(RegionPlanner, PrefersTheWidePassage)
{
  rgmap::RgMap map;
  // Two ways past a block in the middle: a 0.7 m gap below (fits, tight) and a 1.6 m one above.
  // The narrow one is a little shorter; the wall cost makes the wide one the choice.
  add_region(&map, "room", V(0, 0), V(8, 5),
             {{V(0, 0), V(8, 0)}, {V(8, 0), V(8, 5)}, {V(8, 5), V(0, 5)}, {V(0, 5), V(0, 0)}, {V(3.5, 0.7), V(4.5, 0.7)},
              {V(4.5, 0.7), V(4.5, 3.4)}, {V(4.5, 3.4), V(3.5, 3.4)}, {V(3.5, 3.4), V(3.5, 0.7)}},
             [](const V& c) { return c.x() > 3.5 && c.x() < 4.5 && c.y() > 0.7 && c.y() < 3.4; });
  const RegionPlanner rp(map.regions().begin()->second, options().grid);
  const auto path = rp.plan(V(1, 1.5), V(7, 1.5));
  ASSERT_TRUE(path);
  double top = -1;
  for (const auto& p : path->points) top = std::max(top, p.y());
  EXPECT_GT(top, 3.4);
}

TEST(FramedQuadtree, OpenSpaceMakesLargeQuads)
{
  const auto map = one_room_with_wall();
  const RegionGrid grid(map.regions().begin()->second, options().grid);
  const FramedQuadtree tree(grid);
  int free_cells = 0;
  for (int y = 0; y < grid.height(); ++y)
    for (int x = 0; x < grid.width(); ++x) free_cells += grid.free(Cell(x, y));
  // Far fewer quads than cells, and the open middle of the room in a few large ones.
  EXPECT_LT(static_cast<int>(tree.quads().size()) * 3, free_cells);
  int largest = 0;
  for (const auto& q : tree.quads()) largest = std::max(largest, q.size);
  EXPECT_GE(largest, 16);
  for (const auto& q : tree.quads())
    for (int y = q.y0; y < q.y0 + q.size; ++y)
      for (int x = q.x0; x < q.x0 + q.size; ++x) ASSERT_EQ(grid.level(Cell(x, y)), q.level);
}

// The framed quadtree's path costs what the cheapest 8-connected path on the same cells does,
// or less (its straight lines inside quads are shorter than grid steps).
TEST(FramedQuadtree, NoDearerThanTheGridSearch)
{
  const auto map = one_room_with_wall();
  const RegionGrid grid(map.regions().begin()->second, options().grid);
  const FramedQuadtree tree(grid);
  const Cell s = grid.cell_of(V(2, 1)), t = grid.cell_of(V(6, 1.5));
  const auto path = tree.search(s, t);
  ASSERT_TRUE(path);
  double quad_cost = 0;
  for (size_t i = 0; i + 1 < path->size(); ++i)
    quad_cost += *grid.line_cost(grid.center_of((*path)[i]), grid.center_of((*path)[i + 1]));
  // Dijkstra on the 8-connected grid with the same cell costs.
  const int w = grid.width(), h = grid.height();
  std::vector<double> d(static_cast<size_t>(w) * h, 1e18);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  d[static_cast<size_t>(s.y() * w + s.x())] = 0;
  open.push({0, s.y() * w + s.x()});
  while (!open.empty()) {
    const auto [du, u] = open.top();
    open.pop();
    if (du > d[static_cast<size_t>(u)]) continue;
    const Cell cu(u % w, u / w);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const Cell cv(cu.x() + dx, cu.y() + dy);
        if ((dx || dy) && grid.free(cv)) {
          const double step = std::hypot(dx, dy) * grid.resolution() * 0.5 *
                              (grid.level_cost(grid.level(cu)) + grid.level_cost(grid.level(cv)));
          const int v = cv.y() * w + cv.x();
          if (du + step < d[static_cast<size_t>(v)]) {
            d[static_cast<size_t>(v)] = du + step;
            open.push({du + step, v});
          }
        }
      }
  }
  const double grid_cost = d[static_cast<size_t>(t.y() * w + t.x())];
  EXPECT_LT(quad_cost, grid_cost * 1.02);
  EXPECT_GT(quad_cost, grid_cost * 0.85);
}

TEST(GlobalPlanner, RoutesThroughTheDoorAndAroundItWhenClosed)
{
  Ring r = ring();
  GlobalPlanner gp(options());
  gp.set_map(r.map);
  PlanRequest req{r.a, V(2, 1.5), r.b, V(2.5, 1.5)};
  std::string why;
  auto route = gp.plan(req, &why);
  ASSERT_TRUE(route) << why;
  ASSERT_EQ(route->legs.size(), 2u);
  EXPECT_EQ(route->legs[0].exit_gateway, r.door);
  EXPECT_EQ(route->legs[1].region_id, r.b);
  // The leg in B ends at the goal, in B's frame.
  EXPECT_LT((route->legs[1].points.back() - V(2.5, 1.5)).norm(), 1e-9);

  gp.costs().gateway_failed(*r.map.gateway(r.door), 0.0);
  route = gp.plan(req, &why);
  ASSERT_TRUE(route) << why;
  ASSERT_EQ(route->legs.size(), 3u);
  EXPECT_EQ(route->legs[1].region_id, r.h);
  EXPECT_GT(route->length, 8.0);

  // Every way closed: no route, and the reason names the closed gateways.
  gp.costs().gateway_failed(*r.map.gateway(r.ha), 0.0);
  EXPECT_FALSE(gp.plan(req, &why));
  EXPECT_NE(why.find("closed gateways"), std::string::npos) << why;
  // After the retry time the door is tried again (where it is the only way; it costs more now).
  req.now_s = options().global.closed_retry_s + 1;
  EXPECT_FALSE(gp.costs().closed(r.door, req.now_s));
  gp.costs().gateway_failed(*r.map.gateway(r.ha), req.now_s);
  route = gp.plan(req, &why);
  ASSERT_TRUE(route) << why;
  EXPECT_EQ(route->legs[0].exit_gateway, r.door);
}

// The door's opening is unknown to both rooms: the gateway itself makes it passable.
// The node beats its heartbeat from this: planning on a large map took the planner past its
// supervisor's 1 s bound on work without progress under stress-ng.
TEST(GlobalPlanner, ReportsProgressForEveryRegionItWorksIn)
{
  Ring r = ring();
  GlobalPlanner gp(options());
  int calls = 0;
  gp.set_progress([&calls] { ++calls; });
  gp.set_map(r.map);
  EXPECT_EQ(calls, 0);
  std::string why;
  const auto route = gp.plan(PlanRequest{r.a, V(2, 1.5), r.b, V(2.5, 1.5)}, &why);
  ASSERT_TRUE(route) << why;
  EXPECT_GE(calls, 2 * static_cast<int>(route->legs.size())) << "a region planner built and a path searched per leg";
}

TEST(GlobalPlanner, PassesADoorWhoseOpeningNeitherRoomKnows)
{
  Ring r = ring(true);
  GlobalPlanner gp(options());
  gp.set_map(r.map);
  std::string why;
  const auto route = gp.plan({r.a, V(2, 1.5), r.b, V(2.5, 1.5)}, &why);
  ASSERT_TRUE(route) << why;
  ASSERT_EQ(route->legs.size(), 2u);
  EXPECT_EQ(route->legs[0].exit_gateway, r.door);
  EXPECT_LT(route->length, 6.0);
  // Without the gateway's opening the rooms are joined through the hallway only.
  Ring closed = ring(true);
  closed.map.gateway(closed.door)->gateway_points = {V(4.5, 1.5)};
  GlobalPlanner gp2(options());
  gp2.set_map(closed.map);
  const auto around = gp2.plan({closed.a, V(2, 1.5), closed.b, V(2.5, 1.5)}, &why);
  ASSERT_TRUE(around) << why;
  EXPECT_EQ(around->legs.size(), 3u);
}

// A short line inside the door's opening (someone who stood in the doorway when the kernel saw
// it) does not close the door in the room's planning grid; the door's leaf, shut across the
// opening from jamb to jamb, does.
TEST(RegionGrid, LeavesOutWhatStandsInADoorsOpeningButNotAShutDoor)
{
  auto joined = [](const V& a, const V& b) {
    Ring r = ring(true);
    r.map.region(r.a)->segments.push_back({a, b, 0.01, 8});
    GlobalPlanner gp(options());
    gp.set_map(r.map);
    // From the room into the passage (its opening is carved free) straight through the door,
    // not round through room B and the hallway.
    const auto path = gp.region_planner(r.a)->plan(V(3.5, 1.5), V(4.8, 1.5));
    return path && path->length < 2.0;
  };
  EXPECT_TRUE(joined(V(4.2, 1.4), V(4.25, 1.6)));
  EXPECT_FALSE(joined(V(4.0, 1.0), V(4.0, 2.0)));
}

// A start next to a room beside this one (seen through the gateway) is moved onto the region's
// own side, never into the other room.
TEST(RegionGrid, AdaptsOnlyOntoTheRegionsOwnSpace)
{
  rgmap::RgMap map;
  const auto& a = add_region(&map, "upper", V(0, 0), V(4, 3), {{V(0, 0), V(4, 0)}, {V(4, 0), V(4, 3)}, {V(4, 3), V(0, 3)}, {V(0, 3), V(0, 0)}});
  add_region(&map, "lower", V(0, -3.1), V(4, -0.1),
             {{V(0, -0.1), V(4, -0.1)}, {V(4, -0.1), V(4, -3.1)}, {V(4, -3.1), V(0, -3.1)}, {V(0, -3.1), V(0, -0.1)}});
  GlobalPlanner gp(options());
  gp.set_map(map);
  const RegionGrid& grid = gp.region_planner(a.id)->grid();
  // Between the two walls; the lower room's free cells are nearer than the upper's.
  const auto c = grid.nearest_free(grid.cell_of(V(2, -0.12)), 1.0);
  ASSERT_TRUE(c);
  EXPECT_GT(grid.center_of(*c).y(), 0.0);
  EXPECT_TRUE(grid.free(grid.cell_of(V(2, -0.6))));   // seen from beside, but not where a start goes
}

TEST(GlobalPlanner, PrefersHallwayGatewaysToDoorsOnlyWithinTheirCost)
{
  Ring r = ring();
  GlobalPlanner gp(options());
  gp.set_map(r.map);
  const PlanRequest req{r.a, V(2, 1.5), r.b, V(2.5, 1.5)};
  std::string why;
  // A door that failed often costs more than the detour through the hallway (~ 8 m more).
  for (int i = 0; i < 3; ++i) gp.costs().gateway_failed(*r.map.gateway(r.door), -1e6);
  auto route = gp.plan(req, &why);
  ASSERT_TRUE(route) << why;
  EXPECT_EQ(route->legs.size(), 3u);
  // Passed again and again, its extra falls back to the base door cost: the door is taken.
  for (int i = 0; i < 10; ++i) gp.costs().gateway_passed(*r.map.gateway(r.door), 2.0);
  route = gp.plan(req, &why);
  ASSERT_TRUE(route) << why;
  EXPECT_EQ(route->legs.size(), 2u);
}

TEST(GlobalPlanner, UnknownRegionsAndBlockedGoalsAreRefusedWithAReason)
{
  Ring r = ring();
  GlobalPlanner gp(options());
  gp.set_map(r.map);
  std::string why;
  EXPECT_FALSE(gp.plan({r.a, V(2, 1.5), 99, V(0, 0)}, &why));
  EXPECT_NE(why.find("99"), std::string::npos);
  EXPECT_FALSE(gp.plan({r.a, V(2, 1.5), r.b, V(40, 40)}, &why));
  EXPECT_NE(why.find("goal is blocked"), std::string::npos) << why;
  EXPECT_EQ(gp.region_named("room b"), r.b);
  const auto p = gp.region_goal_point(r.b);
  ASSERT_TRUE(p);
  EXPECT_TRUE(gp.region_planner(r.b)->grid().free(gp.region_planner(r.b)->grid().cell_of(*p)));
}

// Exploring (NavGoal::beyond_known): a goal a metre past a doorway the room's freespace ends at
// is reached straight through the doorway; one as far past the wall beside it is not.
TEST(GlobalPlanner, GoalBeyondTheKnownIsReachedThroughAnOpeningNotAWall)
{
  rgmap::RgMap map;
  const auto room = add_region(&map, "room", V(0, 0), V(4, 3),
                               {{V(0, 0), V(4, 0)}, {V(4, 0), V(4, 1)}, {V(4, 2), V(4, 3)}, {V(4, 3), V(0, 3)}, {V(0, 3), V(0, 0)}})
                        .id;
  map.version = 1;
  PlannerOptions o = options();
  GlobalPlanner gp(o);
  gp.set_map(map);
  std::string why;
  PlanRequest through{room, V(1, 1.5), room, V(5.0, 1.5)};
  EXPECT_FALSE(gp.plan(through, &why)) << "without beyond_known the goal is blocked";
  through.goal_reach = o.grid.beyond_known_reach;
  const auto route = gp.plan(through, &why);
  ASSERT_TRUE(route) << why;
  EXPECT_LT((route->legs.back().points.back() - V(5.0, 1.5)).norm(), 1e-9);
  PlanRequest behind_wall{room, V(1, 1.5), room, V(5.0, 0.5)};
  behind_wall.goal_reach = o.grid.beyond_known_reach;
  EXPECT_FALSE(gp.plan(behind_wall, &why));
}

// A room [0, 6] x [0, 4] whose freespace leaves the robot's place at (1.5, 2) a scrap apart: a
// ring of unseen cells round it from 0.3 to 0.4 m (ragged freespace; unknown space round a robot
// whose laser sees only ahead). `walled`: the ring is a wall of the map instead, four lines.
rgmap::RgMap room_with_a_scrap(bool walled, double ring_outer = 0.4)
{
  rgmap::RgMap map;
  const V at(1.5, 2.0);
  std::vector<Wall> walls = {{V(0, 0), V(6, 0)}, {V(6, 0), V(6, 4)}, {V(6, 4), V(0, 4)}, {V(0, 4), V(0, 0)}};
  if (walled)
    for (const auto& [a, b] : std::vector<Wall>{{V(-0.35, -0.35), V(0.35, -0.35)}, {V(0.35, -0.35), V(0.35, 0.35)},
                                                {V(0.35, 0.35), V(-0.35, 0.35)}, {V(-0.35, 0.35), V(-0.35, -0.35)}})
      walls.push_back({at + a, at + b});
  add_region(&map, "room", V(0, 0), V(6, 4), walls, [&](const V& c) {
    const double d = (c - at).norm();
    return !walled && d > 0.3 && d < ring_outer;
  });
  map.version = 1;
  return map;
}

// The robot stands on a scrap of free cells apart from the room's space: the nearest free cell
// is the scrap's, and a path from it leads nowhere. Its body stands there, so it steps straight
// into the room's space (through no line of the map) and the goal is reached. Walled in, it is
// cut off, and the NO_PATH says so: standing there, nothing changes.
TEST(GlobalPlanner, TheRobotStepsOffAScrapOfFreeSpaceButNotThroughAWall)
{
  const auto scrap = room_with_a_scrap(false);
  const int64_t room = scrap.regions().begin()->first;
  GlobalPlanner gp(options());
  gp.set_map(scrap);
  const RegionGrid& grid = gp.region_planner(room)->grid();
  const auto own = grid.nearest_free(grid.cell_of(V(1.5, 2.0)));
  ASSERT_TRUE(own);
  EXPECT_NE(grid.component(*own), grid.main_component()) << "the robot's place is a scrap apart";
  std::string why;
  const auto route = gp.plan({room, V(1.5, 2.0), room, V(4.5, 2.0)}, &why);
  ASSERT_TRUE(route) << why;
  EXPECT_LT((route->legs.front().points.front() - V(1.5, 2.0)).norm(), 1e-9);
  EXPECT_LT(route->length, 3.8);

  const auto walled = room_with_a_scrap(true);
  GlobalPlanner gw(options());
  gw.set_map(walled);
  EXPECT_FALSE(gw.plan({room, V(1.5, 2.0), room, V(4.5, 2.0)}, &why));
  EXPECT_EQ(no_path_cause(why), NoPathCause::kStartCutOff) << why;
  EXPECT_TRUE(gw.region_planner(room)->cut_off(V(1.5, 2.0)));
  EXPECT_FALSE(gw.region_planner(room)->cut_off(V(4.5, 2.0)));
  EXPECT_FALSE(gw.plan({room, V(1.5, 2.0), room, V(2.5, 2.0)}, &why)) << "a step through the wall";

  // Unseen space too wide round it to step off within adapt_distance: cut off for a goal across
  // the room, but a goal a step away (robot_step) with no line between is gone to straight.
  const auto wide = room_with_a_scrap(false, 0.8);
  GlobalPlanner gs(options());
  gs.set_map(wide);
  EXPECT_FALSE(gs.plan({room, V(1.5, 2.0), room, V(4.5, 2.0)}, &why));
  EXPECT_EQ(no_path_cause(why), NoPathCause::kStartCutOff) << why;
  const auto step = gs.plan({room, V(1.5, 2.0), room, V(2.5, 2.0)}, &why);
  ASSERT_TRUE(step) << why;
  EXPECT_NEAR(step->length, 1.0, 1e-6);
}

// The robot stands where the map knows nothing round it, too widely to step off (collision
// avoidance took it aside for a person): it came there, so the way it came is free. Its own
// track (newest first) leads the route back to where the map has room; a track across a line
// of the map (a localization jump through a wall) is not taken.
TEST(GlobalPlanner, ARobotCutOffGoesBackAlongItsOwnTrack)
{
  const auto wide = room_with_a_scrap(false, 0.8);
  const int64_t room = wide.regions().begin()->first;
  std::vector<V> track;   // it drove from (3.5, 2) to (1.5, 2)
  for (double x = 1.6; x <= 3.5 + 1e-9; x += 0.1) track.push_back(V(x, 2.0));
  GlobalPlanner gp(options());
  gp.set_map(wide);
  std::string why;
  PlanRequest req{room, V(1.5, 2.0), room, V(4.5, 2.0)};
  ASSERT_FALSE(gp.plan(req, &why)) << "without its track, cut off";
  req.track = track;
  const auto route = gp.plan(req, &why);
  ASSERT_TRUE(route) << why;
  const auto& points = route->legs.front().points;
  EXPECT_LT((points.front() - V(1.5, 2.0)).norm(), 1e-9) << "from where it stands";
  ASSERT_GE(points.size(), 3u);
  EXPECT_LT((points[1] - V(1.6, 2.0)).norm(), 1e-9) << "back along the track";
  EXPECT_LT(route->length, 3.5);
  EXPECT_NEAR(route->legs.front().length, route->length, 1e-9);
  // Away from its track (it came the other way round): the track is no help where it leads
  // only through more unknown space beyond reach.
  req.track = {V(1.5, 2.1), V(1.5, 2.2)};
  EXPECT_FALSE(gp.plan(req, &why));
  EXPECT_EQ(no_path_cause(why), NoPathCause::kStartCutOff) << why;

  const auto walled = room_with_a_scrap(true);
  GlobalPlanner gw(options());
  gw.set_map(walled);
  req.track.clear();
  for (const V& q : track)
    if (q.x() > 2.3) req.track.push_back(q);   // the pose jumped out through the wall
  ASSERT_TRUE(gw.region_planner(room)->crosses_line(req.start, req.track.front()));
  ASSERT_FALSE(gw.region_planner(room)->cut_off(req.track.front()));
  EXPECT_FALSE(gw.plan(req, &why)) << "a track through the wall";
  EXPECT_EQ(no_path_cause(why), NoPathCause::kStartCutOff) << why;
}

// The hall of the test below: L, R and the hallway; `l_extra`: lines only L has mapped.
struct OverlappingHall
{
  rgmap::RgMap map;
  int64_t l = 0, r = 0, hallway = 0;
};
OverlappingHall overlapping_hall(const std::vector<Wall>& l_extra = {})
{
  OverlappingHall o;
  const std::vector<Wall> hall = {{V(0, 4), V(8, 4)}, {V(0, 0), V(0, 4)}, {V(8, 0), V(8, 4)},
                                  {V(0, 0), V(1, 0)}, {V(2.2, 0), V(5.8, 0)}, {V(7, 0), V(8, 0)}};
  std::vector<Wall> l_lines = hall;
  l_lines.insert(l_lines.end(), l_extra.begin(), l_extra.end());
  o.l = add_region(&o.map, "L", V(0, 0), V(5, 4), l_lines).id;
  o.r = add_region(&o.map, "R", V(3, 0), V(8, 4), hall).id;
  o.hallway = add_region(&o.map, "hallway", V(0, -2), V(8, 0), {{V(0, -2), V(8, -2)}, {V(0, -2), V(0, 0)}, {V(8, -2), V(8, 0)}}).id;
  add_gateway(&o.map, rgmap::GatewayClass::kOpening, o.hallway, o.l, V(1.6, 0));
  add_gateway(&o.map, rgmap::GatewayClass::kOpening, o.hallway, o.r, V(6.4, 0));
  o.map.version = 1;
  return o;
}

// A hall's floor split between two overlapping regions, L [0,5]x[0,4] and R [3,8]x[0,4], with no
// gateway between them; each opens onto a hallway below. The robot stands in L where R's free
// space holds it too: the route starts in R and goes straight to a goal in R, not out through
// L's opening, along the hallway and in through R's (to and fro).
TEST(GlobalPlanner, AStartInOverlappingRegionsTakesTheCheapestOfThem)
{
  const OverlappingHall hall = overlapping_hall();
  const int64_t l = hall.l, r = hall.r;
  GlobalPlanner gp(options());
  gp.set_map(hall.map);
  std::string why;
  const auto route = gp.plan({l, V(4.5, 2.0), r, V(4.0, 2.0)}, &why);
  ASSERT_TRUE(route) << why;
  ASSERT_EQ(route->legs.size(), 1u);
  EXPECT_EQ(route->legs[0].region_id, r);
  EXPECT_LT((route->legs[0].points.front() - V(1.5, 2.0)).norm(), 1e-9) << "from where it stands, in R's frame";
  EXPECT_LT(route->length, 3.0);
  // From where only L holds the robot, the way is through the hallway.
  const auto around = gp.plan({l, V(1.5, 2.0), r, V(4.0, 2.0)}, &why);
  ASSERT_TRUE(around) << why;
  EXPECT_EQ(around->legs.front().region_id, l);

  // L has mapped a wall at x = 4 that R has not (each grid draws its own lines): R's straight
  // way from the robot would cross it, so the route does not start in R.
  const OverlappingHall walled = overlapping_hall({{V(4.0, 0.0), V(4.0, 3.0)}});
  GlobalPlanner gw(options());
  gw.set_map(walled.map);
  const auto own = gw.plan({walled.l, V(3.6, 1.5), walled.r, V(4.0, 1.5)}, &why);
  ASSERT_TRUE(own) << why;
  EXPECT_EQ(own->legs.front().region_id, walled.l) << "not through L's wall in R's grid";
}

// NO_PATH's reason begins with its cause: the goal out of reach, or only gateways taken for
// closed in the way (the same goal once they reopen).
TEST(GlobalPlanner, NoPathSaysWhetherTheGoalIsOutOfReachOrBehindAClosedGateway)
{
  Ring r = ring();
  GlobalPlanner gp(options());
  gp.set_map(r.map);
  std::string why;
  EXPECT_FALSE(gp.plan({r.a, V(2, 1.5), r.b, V(40, 40)}, &why));
  EXPECT_EQ(no_path_cause(why), NoPathCause::kGoalUnreachable) << why;
  EXPECT_FALSE(gp.plan({r.a, V(2, 1.5), 99, V(0, 0)}, &why));
  EXPECT_EQ(no_path_cause(why), NoPathCause::kGoalUnreachable) << why;
  gp.costs().gateway_failed(*r.map.gateway(r.door), 0.0);
  gp.costs().gateway_failed(*r.map.gateway(r.ha), 0.0);
  EXPECT_FALSE(gp.plan({r.a, V(2, 1.5), r.b, V(2.5, 1.5)}, &why));
  EXPECT_EQ(no_path_cause(why), NoPathCause::kClosedGateway) << why;
  EXPECT_NE(why.find("closed gateways"), std::string::npos) << why;
}

// Collision avoidance cannot pass away from any gateway (what the line map holds too thinly):
// the place ahead on the route becomes an obstacle for a while and the route goes round it.
TEST(GlobalPlanner, ABlockedPlaceIsGoneRoundUntilItsTime)
{
  const auto map = one_room_with_wall();
  const int64_t room = map.regions().begin()->first;
  PlannerOptions o = options();
  o.grid.blocked_radius = 0.25;
  GlobalPlanner gp(o);
  gp.set_map(map);
  std::string why;
  const PlanRequest req{room, V(2, 4.2), room, V(6, 4.2)};
  auto route = gp.plan(req, &why);
  ASSERT_TRUE(route) << why;
  const double straight = route->length;
  EXPECT_LT(straight, 4.5) << "over the top of the inner wall";
  gp.block_place(room, V(4, 4.3), 30.0);
  PlanRequest strict = req;
  strict.strict_places = true;
  EXPECT_FALSE(gp.plan(strict, &why)) << "the only way, between the wall's end and the room's: blocked";
  EXPECT_EQ(no_path_cause(why), NoPathCause::kBlockedPlace) << why;
  PlanRequest nowhere = strict;
  nowhere.goal = V(40, 40);
  EXPECT_FALSE(gp.plan(nowhere, &why));
  EXPECT_EQ(no_path_cause(why), NoPathCause::kGoalUnreachable) << "out of reach whatever the place: " << why;
  // No way round: through the place rather than nowhere (whoever stood there may have gone);
  // the place is kept for routes that have a way round it.
  route = gp.plan(req, &why);
  ASSERT_TRUE(route) << why;
  EXPECT_NEAR(route->length, straight, 1e-6);
  EXPECT_EQ(gp.blocked_places(), 1u);
  PlanRequest later = req;
  later.now_s = 31.0;
  route = gp.plan(later, &why);
  ASSERT_TRUE(route) << why;
  EXPECT_NEAR(route->length, straight, 1e-6);
  EXPECT_EQ(gp.blocked_places(), 0u);
}

// A hold beyond closed_retry_s steers routes round a gateway: while another way is left it is
// kept, and where held gateways are all that is in the way, the one whose last failure is
// closed_retry_s old is planned through again (a robot whose only door failed three times in a
// row waited four times as long with nothing else to do).
TEST(GlobalPlanner, AGatewayHeldLongIsTriedAfterTheBaseHoldWhenNoOtherWayIsLeft)
{
  Ring r = ring();
  const double retry = options().global.closed_retry_s;
  GlobalPlanner gp(options());
  gp.set_map(r.map);
  for (double t : {0.0, 100.0, 200.0}) gp.costs().gateway_failed(*r.map.gateway(r.door), t);
  PlanRequest req{r.a, V(2, 1.5), r.b, V(2.5, 1.5)};
  req.now_s = 200.0 + retry + 1;
  ASSERT_TRUE(gp.costs().closed(r.door, req.now_s));
  std::string why;
  auto route = gp.plan(req, &why);
  ASSERT_TRUE(route) << why;
  EXPECT_NE(route->legs[0].exit_gateway, r.door) << "another way is left: round the door";
  // The hallway's opening held too (just now): the door is the way again.
  gp.costs().gateway_failed(*r.map.gateway(r.ha), req.now_s);
  route = gp.plan(req, &why);
  ASSERT_TRUE(route) << why;
  EXPECT_EQ(route->legs[0].exit_gateway, r.door);
  // Within closed_retry_s of the door's last failure it is not tried: no route, for that reason.
  req.now_s = 200.0 + 0.5 * retry;
  EXPECT_FALSE(gp.plan(req, &why));
  EXPECT_EQ(no_path_cause(why), NoPathCause::kClosedGateway) << why;
}

TEST(EdgeCosts, OnlyWhatCanStayShutIsClosedLongerWithEveryFailure)
{
  Ring r = ring();
  EdgeCosts c(options().global);
  const double retry = options().global.closed_retry_s;
  // The door failed three times in a row: closed four times as long the third time.
  for (double t : {0.0, 100.0, 200.0}) c.gateway_failed(*r.map.gateway(r.door), t);
  EXPECT_TRUE(c.closed(r.door, 200.0 + 3.5 * retry));
  // The hallway's opening, as often: people held it, each time for closed_retry_s only.
  for (double t : {0.0, 100.0, 200.0}) c.gateway_failed(*r.map.gateway(r.ha), t);
  EXPECT_TRUE(c.closed(r.ha, 200.0 + 0.5 * retry));
  EXPECT_FALSE(c.closed(r.ha, 200.0 + retry + 1));
}

TEST(EdgeCosts, SavesAndRestoresWhatWasLearned)
{
  Ring r = ring();
  EdgeCosts c(options().global);
  c.gateway_failed(*r.map.gateway(r.door), 100.0);
  c.gateway_passed(*r.map.gateway(r.ha), 3.5);
  c.region_traversed(r.h, r.ha, r.hb, 14.0);
  EdgeCosts d(options().global);
  d.from_json(c.to_json());
  EXPECT_TRUE(d.closed(r.door, 120.0));
  EXPECT_FALSE(d.closed(r.door, 100.0 + options().global.closed_retry_s + 1));
  // A second failure in a row keeps it closed twice as long.
  d.gateway_failed(*r.map.gateway(r.door), 200.0);
  EXPECT_TRUE(d.closed(r.door, 200.0 + 1.5 * options().global.closed_retry_s));
  EXPECT_DOUBLE_EQ(*d.gateway_cost(*r.map.gateway(r.ha), 0), 3.5);
  EXPECT_TRUE(d.measured(r.h, r.hb, r.ha));
  EXPECT_DOUBLE_EQ(d.region_cost(r.h, r.hb, r.ha, 1.0), 14.0);
  nlohmann::json bad = c.to_json();
  bad["gateways"][0]["time_s"] = "x";
  EXPECT_THROW(d.from_json(bad), std::invalid_argument);
}

TEST(Route, TargetsAreHalfAMetreToOneAndAHalfApart)
{
  Ring r = ring();
  GlobalPlanner gp(options());
  gp.set_map(r.map);
  std::string why;
  gp.costs().gateway_failed(*r.map.gateway(r.door), 0.0);
  const auto route = gp.plan({r.a, V(2, 1.5), r.b, V(2.5, 1.5)}, &why);
  ASSERT_TRUE(route) << why;
  const auto targets = cut_targets(*route, 0.5, 1.5);
  ASSERT_GE(targets.size(), 6u);
  for (size_t i = 1; i < targets.size(); ++i) {
    const double step = targets[i].arc - targets[i - 1].arc;
    EXPECT_GE(step, 0.5 - 1e-9);
    EXPECT_LE(step, 1.5 + 1e-9);
  }
  EXPECT_NEAR(targets.back().arc, route->length, 1e-6);
  EXPECT_EQ(targets.back().leg, route->legs.size() - 1);
  EXPECT_LT((targets.back().pose.translation() - V(2.5, 1.5)).norm(), 1e-9);
}

TEST(RouteTime, PredictsTheDriveUnderTheLimits)
{
  trajectory::Limits limits;
  limits.v_max = 0.6;
  limits.a_max = 0.4;
  Route straight;
  straight.legs.push_back({});
  straight.legs[0].points = {V(0, 0), V(5, 0)};
  straight.legs[0].length = 5;
  straight.length = 5;
  // Accelerate, cruise, brake: 5 / 0.6 + 0.6 / 0.4.
  EXPECT_NEAR(predicted_time(straight, limits), 5 / 0.6 + 0.6 / 0.4, 0.05);
  // The same length with a right angle in the middle takes longer (slower through the bend),
  // and a second leg is placed through the gateway's transform.
  Route bend = straight;
  bend.legs[0].points = {V(0, 0), V(2.5, 0)};
  bend.legs[0].this_from_next = Pose2(2.5, 0, M_PI / 2);
  bend.legs.push_back({});
  bend.legs[1].points = {V(0, 0), V(2.5, 0)};
  const double t = predicted_time(bend, limits);
  EXPECT_GT(t, predicted_time(straight, limits) + 0.3);
  EXPECT_LT(t, predicted_time(straight, limits) + 6.0);
}

// A robot that drives straight to the first target at 0.5 m/s (no obstacles), its odometry
// frame offset from the map.
struct FollowingRobot
{
  Pose2 map_from_base;
  Pose2 odom_from_map{1.0, -2.0, 0.3};
  std::function<bool(const V&)> wall;   // where it cannot go (a shut door)
  // False when the step was refused: collision avoidance would report it cannot pass.
  bool drive(const TargetList& t, double dt)
  {
    if (t.odom_from_target.empty()) return true;
    const V target = odom_from_map.inverse() * t.odom_from_target.front().translation();
    const V d = target - map_from_base.translation();
    const double step = std::min(d.norm(), 0.5 * dt);
    if (d.norm() < 1e-9) return true;
    const V next = map_from_base.translation() + d.normalized() * step;
    if (wall && wall(next)) return false;
    map_from_base = Pose2(next, std::atan2(d.y(), d.x()));
    return true;
  }
};

RobotPose pose_of(const Ring& r, const FollowingRobot& robot, int64_t utime)
{
  // The region whose box holds the robot (regions are offsets of the map frame here).
  const V p = robot.map_from_base.translation();
  int64_t region = p.y() < 0 ? r.h : (p.x() < 4.5 ? r.a : r.b);
  RobotPose pose;
  pose.utime = utime;
  pose.region_id = region;
  pose.region_from_base = r.map.region(region)->map_from_region.inverse() * robot.map_from_base;
  pose.odom_from_base = robot.odom_from_map * robot.map_from_base;
  return pose;
}

// A goal at (x, y) in region `region`'s frame.
NavGoal pose_goal(int64_t id, int64_t region, double x, double y)
{
  NavGoal goal;
  goal.goal_id = id;
  goal.region_id = region;
  goal.has_pose = true;
  goal.region_from_goal = Pose2(x, y, 0);
  return goal;
}

GoalStatus drive_goal(Planner* planner, const std::function<RobotPose(const FollowingRobot&, int64_t)>& pose_of_robot,
                      FollowingRobot* robot, int64_t* utime, double seconds)
{
  TargetList last;
  bool blocked = false;
  for (int i = 0; i < seconds * 10; ++i) {
    *utime += 100'000;
    planner->on_pose(pose_of_robot(*robot, *utime));
    planner->on_blocked(*utime, blocked);
    const auto out = planner->update(*utime);
    if (out.targets) last = *out.targets;
    if (getenv("PLANNER_TEST_TRACE") && i % 10 == 0)
      fprintf(stderr, "t %.1f at %.2f %.2f status %s replans %lld targets %zu\n", i * 0.1, robot->map_from_base.x(),
              robot->map_from_base.y(), to_string(planner->status()), (long long)planner->replans(), last.odom_from_target.size());
    if (planner->status() != GoalStatus::kActive) return planner->status();
    blocked = !robot->drive(last, 0.1);
  }
  return planner->status();
}

GoalStatus drive_goal(Planner* planner, const Ring& r, FollowingRobot* robot, int64_t* utime, double seconds)
{
  return drive_goal(
      planner, [&r](const FollowingRobot& robot, int64_t utime) { return pose_of(r, robot, utime); }, robot, utime, seconds);
}

TEST(Planner, DrivesToANamedRoomThroughTheDoor)
{
  Ring r = ring();
  Planner planner(options());
  planner.set_map(r.map);
  FollowingRobot robot;
  robot.map_from_base = Pose2(2, 1.5, 0);
  int64_t utime = kUtime;
  NavGoal goal;
  goal.goal_id = 1;
  goal.region_name = "Room B";
  planner.set_goal(goal, utime);
  EXPECT_EQ(drive_goal(&planner, r, &robot, &utime, 60), GoalStatus::kReached);
  EXPECT_GT(robot.map_from_base.x(), 5.0);
  EXPECT_GT(robot.map_from_base.y(), 0.0);
  // The door was crossed and timed.
  EXPECT_GT(planner.global().costs().changes(), 0);
}

TEST(Planner, AClosedDoorIsGoneAroundAndNoPathWhenThereIsNoOtherWay)
{
  Ring r = ring();
  Planner planner(options());
  planner.set_map(r.map);
  FollowingRobot robot;
  robot.map_from_base = Pose2(2, 1.5, 0);
  int64_t utime = kUtime;
  NavGoal goal = pose_goal(7, r.b, 2.5, 1.5);
  planner.set_goal(goal, utime);
  // The door stays shut: before it, collision avoidance reports it cannot pass.
  robot.wall = [](const V& p) { return p.x() > 3.7 && p.x() < 5.3 && p.y() > 0.5; };
  EXPECT_EQ(drive_goal(&planner, r, &robot, &utime, 120), GoalStatus::kReached);
  EXPECT_GE(planner.replans(), 1);
  EXPECT_LT(robot.map_from_base.x(), 8.0);
  EXPECT_TRUE(planner.global().costs().closed(r.door, utime * 1e-6));

  // Back in A with the hallway openings closed too: no path, with the reason.
  Ring closed = ring();
  Planner p2(options());
  p2.set_map(closed.map);
  p2.global().costs().gateway_failed(*closed.map.gateway(closed.ha), utime * 1e-6);
  p2.global().costs().gateway_failed(*closed.map.gateway(closed.door), utime * 1e-6);
  FollowingRobot r2;
  r2.map_from_base = Pose2(2, 1.5, 0);
  goal.goal_id = 8;
  p2.set_goal(goal, utime);
  EXPECT_EQ(drive_goal(&p2, closed, &r2, &utime, 5), GoalStatus::kNoPath);
}

// The only way is a doorway where collision avoidance cannot pass (people standing in it, or a
// shut door): the robot waits closed_after_s before the planner gives up with NO_PATH.
TEST(Planner, WaitsAtTheOnlyDoorBeforeCallingItClosed)
{
  Ring r = ring();
  Planner planner(options());
  planner.set_map(r.map);
  int64_t utime = kUtime;
  // The hallway's opening is shut for the whole test: an opening counts as closed for
  // closed_retry_s after its last failure, so it fails "in the future" (the test lasts <= 120 s).
  planner.global().costs().gateway_failed(*r.map.gateway(r.ha), utime * 1e-6 + 120.0);
  FollowingRobot robot;
  robot.map_from_base = Pose2(2, 1.5, 0);
  robot.wall = [](const V& p) { return p.x() > 3.7 && p.x() < 5.3 && p.y() > 0.5; };
  NavGoal goal = pose_goal(9, r.b, 2.5, 1.5);
  planner.set_goal(goal, utime);
  const int64_t start = utime;
  EXPECT_EQ(drive_goal(&planner, r, &robot, &utime, 120), GoalStatus::kNoPath);
  const double waited = (utime - start) * 1e-6;
  EXPECT_GE(waited, options().execution.closed_after_s);
  EXPECT_LT(waited, options().execution.closed_after_s + 15.0);
  EXPECT_TRUE(planner.global().costs().closed(r.door, utime * 1e-6));
}

// A person stands in the doorway a while: the way round through the hallway costs more than
// waiting as long as a gateway is waited for (closed_after_s, short here), so the robot waits
// and goes through the door once they have gone (before, any way round was taken at once).
TEST(Planner, WaitsAtAGatewayRatherThanTakeAWayRoundDearerThanTheWait)
{
  Ring r = ring();
  PlannerOptions o = options();
  o.execution.closed_after_s = 10.0;
  Planner planner(o);
  planner.set_map(r.map);
  int64_t utime = kUtime;
  const int64_t start = utime;
  FollowingRobot robot;
  robot.map_from_base = Pose2(2, 1.5, 0);
  robot.wall = [&](const V& p) { return (utime - start) * 1e-6 < 12.0 && p.x() > 3.7 && p.x() < 5.3 && p.y() > 0.5; };
  planner.set_goal(pose_goal(4, r.b, 2.5, 1.5), utime);
  double lowest_y = robot.map_from_base.y();
  const auto pose_and_lowest = [&](const FollowingRobot& robot, int64_t utime) {
    lowest_y = std::min(lowest_y, robot.map_from_base.y());
    return pose_of(r, robot, utime);
  };
  EXPECT_EQ(drive_goal(&planner, pose_and_lowest, &robot, &utime, 60), GoalStatus::kReached) << planner.reason();
  EXPECT_GT(lowest_y, 0.5) << "went round through the hallway";
  EXPECT_GT((utime - start) * 1e-6, 12.0);
}

// Something collision avoidance cannot pass stands in the only way (the gap between the inner
// wall's end and the room's wall), away from any gateway: the goal has NO_PATH behind the blocked
// place (a while: the same goal can be planned once the place is let go), not because the robot
// were cut off (the place cuts the room's space in two, and the robot's half is still the
// room's); a new goal behind the place, while it is still
// marked, is routed through it (no other way) and reached once the way is clear.
TEST(Planner, ABlockedPlaceWithNoWayRoundEndsTheGoalButNotTheNext)
{
  const auto map = one_room_with_wall();
  const int64_t room = map.regions().begin()->first;
  PlannerOptions o = options();
  o.grid.blocked_radius = 0.25;
  const auto in_room = [room](const FollowingRobot& robot, int64_t utime) {
    return RobotPose{utime, room, robot.map_from_base, robot.odom_from_map * robot.map_from_base};
  };
  Planner planner(o);
  planner.set_map(map);
  int64_t utime = kUtime;
  const int64_t start = utime;
  FollowingRobot robot;
  robot.map_from_base = Pose2(2, 4.2, 0);
  robot.wall = [&](const V& p) { return (utime - start) * 1e-6 < 12.0 && p.x() > 3.2 && p.x() < 4.8 && p.y() > 3.5; };
  planner.set_goal(pose_goal(1, room, 6, 4.2), utime);
  EXPECT_EQ(drive_goal(&planner, in_room, &robot, &utime, 60), GoalStatus::kNoPath);
  EXPECT_EQ(no_path_cause(planner.reason()), NoPathCause::kBlockedPlace) << planner.reason();
  EXPECT_LT((utime - start) * 1e-6, o.execution.blocked_after_s + 5.0);
  EXPECT_EQ(planner.global().blocked_places(), 1u);
  planner.set_goal(pose_goal(2, room, 6, 4.2), utime);
  EXPECT_EQ(drive_goal(&planner, in_room, &robot, &utime, 60), GoalStatus::kReached) << planner.reason();
  EXPECT_LT((utime - start) * 1e-6, o.global.closed_retry_s) << "through the place while it was still marked";
}

// A goal where the robot stands that asks only for another heading (the explorer's look
// behind): a turn on the spot, even where the robot's place is cut off from the region's free
// space; the target lies out along the heading (collision avoidance turns toward it on the
// spot), and the goal is reached, the targets withdrawn, once the heading is.
TEST(Planner, TurnsOnTheSpotWhereOnlyTheHeadingDiffers)
{
  const auto map = room_with_a_scrap(true);
  const int64_t room = map.regions().begin()->first;
  Planner planner(options());
  planner.set_map(map);
  int64_t utime = kUtime;
  const Pose2 odom_from_region(1.0, -2.0, 0.3);
  RobotPose pose{utime, room, Pose2(1.5, 2.0, 0.2), odom_from_region * Pose2(1.5, 2.0, 0.2)};
  planner.on_pose(pose);
  NavGoal look;
  look.goal_id = 5;
  look.region_id = room;
  look.has_pose = true;
  look.region_from_goal = Pose2(1.5, 2.0, 0.2 + M_PI);
  look.position_tolerance = 0.5;
  look.heading_tolerance = 0.35;
  planner.set_goal(look, utime);
  auto out = planner.update(utime);
  ASSERT_TRUE(out.path);
  EXPECT_EQ(out.path->status, GoalStatus::kActive) << out.path->reason;
  ASSERT_TRUE(out.targets);
  ASSERT_EQ(out.targets->odom_from_target.size(), 1u);
  EXPECT_TRUE(out.targets->final_is_goal);
  const Pose2 target = odom_from_region.inverse() * out.targets->odom_from_target[0];
  EXPECT_GT((target.translation() - V(1.5, 2.0)).norm(), 0.3) << "out along the heading";
  EXPECT_LT((target.translation() - (V(1.5, 2.0) + 0.5 * V(std::cos(0.2 + M_PI), std::sin(0.2 + M_PI)))).norm(), 0.05);
  // Half way round: still turning. Round: reached, nothing more to pursue.
  for (const double heading : {1.7, 0.2 + M_PI - 0.2}) {
    utime += 1'000'000;
    pose = {utime, room, Pose2(1.5, 2.0, heading), odom_from_region * Pose2(1.5, 2.0, heading)};
    planner.on_pose(pose);
    out = planner.update(utime);
  }
  EXPECT_EQ(planner.status(), GoalStatus::kReached);
  ASSERT_TRUE(out.targets);
  EXPECT_TRUE(out.targets->odom_from_target.empty());
  // A goal elsewhere from the walled-in place: NO_PATH, the start cut off.
  planner.set_goal(pose_goal(6, room, 4.5, 2.0), utime);
  out = planner.update(utime += 100'000);
  EXPECT_EQ(planner.status(), GoalStatus::kNoPath);
  ASSERT_TRUE(out.path);
  EXPECT_EQ(no_path_cause(out.path->reason), NoPathCause::kStartCutOff) << out.path->reason;
}

TEST(Planner, TargetsAreInTheOdometryFrameAndCancelStopsThem)
{
  Ring r = ring();
  Planner planner(options());
  planner.set_map(r.map);
  FollowingRobot robot;
  robot.map_from_base = Pose2(1, 1.5, 0);
  int64_t utime = kUtime;
  NavGoal goal = pose_goal(3, r.a, 3.5, 1.5);
  planner.set_goal(goal, utime);
  planner.on_pose(pose_of(r, robot, utime));
  const auto out = planner.update(utime);
  ASSERT_TRUE(out.path);
  EXPECT_EQ(out.path->status, GoalStatus::kActive);
  ASSERT_TRUE(out.targets);
  ASSERT_FALSE(out.targets->odom_from_target.empty());
  EXPECT_TRUE(out.targets->final_is_goal);
  const V last_map = robot.odom_from_map.inverse() * out.targets->odom_from_target.back().translation();
  EXPECT_LT((last_map - V(3.5, 1.5)).norm(), 1e-6);
  planner.cancel(3, utime + 1000);
  const auto after = planner.update(utime + 2000);
  ASSERT_TRUE(after.path);
  EXPECT_EQ(after.path->status, GoalStatus::kCancelled);
  ASSERT_TRUE(after.targets);
  EXPECT_TRUE(after.targets->odom_from_target.empty());
}

// While a replan is due (the map's current region is one the route does not cross, before the
// next replan may run) the targets stay where they are: the pose's region is placed through
// the map frame, not taken for the leg's.
TEST(Planner, TargetsStayPutWhileThePoseIsInAnotherRegionThanTheRoute)
{
  Ring r = ring();
  Planner planner(options());
  planner.set_map(r.map);
  FollowingRobot robot;
  robot.map_from_base = Pose2(1.6, 0.3, 0);   // in room A's box and in the hallway's
  int64_t utime = kUtime;
  planner.set_goal(pose_goal(3, r.a, 3.5, 1.5), utime);
  RobotPose pose = pose_of(r, robot, utime);
  pose.region_id = r.a;
  pose.region_from_base = r.map.region(r.a)->map_from_region.inverse() * robot.map_from_base;
  planner.on_pose(pose);
  ASSERT_TRUE(planner.update(utime).targets);
  // The map now says the robot is in the hallway.
  utime += 600'000;
  pose.utime = utime;
  pose.region_id = r.h;
  pose.region_from_base = r.map.region(r.h)->map_from_region.inverse() * robot.map_from_base;
  planner.on_pose(pose);
  const auto out = planner.update(utime);
  ASSERT_TRUE(out.targets);
  ASSERT_FALSE(out.targets->odom_from_target.empty());
  const V last_map = robot.odom_from_map.inverse() * out.targets->odom_from_target.back().translation();
  EXPECT_LT((last_map - V(3.5, 1.5)).norm(), 1e-6);
}

// The localizer still has the robot in room A, which it left: it stands well inside room B,
// beyond room A's grid. The route starts in the region whose free space holds the robot, and the
// planner follows it with the pose in room A's frame (through the map frame) to the goal.
TEST(Planner, StartsWhereTheRobotStandsWhenItsRegionHasNoRoomForIt)
{
  Ring r = ring(true);
  const V robot_map(8.0, 1.5), goal_map(6.0, 1.5);
  const Pose2 map_from_b = r.map.region(r.b)->map_from_region;
  {
    GlobalPlanner gp(options());
    gp.set_map(r.map);
    ASSERT_TRUE(gp.region_planner(r.a)->cut_off(robot_map)) << "room A's frame is the map frame";
    std::string why;
    const auto route = gp.plan(PlanRequest{r.a, robot_map, r.b, map_from_b.inverse() * goal_map}, &why);
    ASSERT_TRUE(route) << why;
    ASSERT_EQ(route->legs.size(), 1u);
    EXPECT_EQ(route->legs[0].region_id, r.b);
    EXPECT_LT((route->legs[0].points.front() - map_from_b.inverse() * robot_map).norm(), 1e-9);
  }
  Planner planner(options());
  planner.set_map(r.map);
  FollowingRobot robot;
  robot.map_from_base = Pose2(robot_map, M_PI);
  int64_t utime = kUtime;
  const V goal_b = map_from_b.inverse() * goal_map;
  planner.set_goal(pose_goal(4, r.b, goal_b.x(), goal_b.y()), utime);
  TargetList last;
  for (int i = 0; i < 100 && planner.status() == GoalStatus::kActive; ++i) {
    utime += 100'000;
    RobotPose pose = pose_of(r, robot, utime);
    pose.region_id = r.a;   // never handed over
    pose.region_from_base = robot.map_from_base;
    planner.on_pose(pose);
    const auto out = planner.update(utime);
    if (out.targets) last = *out.targets;
    robot.drive(last, 0.1);
  }
  EXPECT_EQ(planner.status(), GoalStatus::kReached) << planner.reason();
  EXPECT_EQ(planner.replans(), 1) << "planned once, never off the route";
  EXPECT_LT((robot.map_from_base.translation() - goal_map).norm(), 0.3);
}

// The Planner keeps the robot's track from its poses: a robot that drove into space the map
// never saw is routed back the way it came; one whose pose jumped there (the localizer
// corrected itself) has no track to the place, and is cut off.
TEST(Planner, ARobotCutOffIsRoutedBackTheWayItCame)
{
  const auto wide = room_with_a_scrap(false, 0.8);
  const int64_t room = wide.regions().begin()->first;
  const auto run = [&](bool jump) {
    Planner planner(options());
    planner.set_map(wide);
    int64_t utime = kUtime;
    const auto at = [&](double x) {
      utime += 50'000;
      planner.on_pose({utime, room, Pose2(x, 2.0, M_PI), Pose2(x, 2.0, M_PI)});
    };
    if (jump) {
      at(3.5);
    } else {
      for (double x = 3.5; x >= 1.5 - 1e-9; x -= 0.03) at(x);
    }
    at(1.5);
    planner.set_goal(pose_goal(5, room, 4.5, 2.0), utime);
    planner.update(utime);
    return std::make_pair(planner.status(), planner.reason());
  };
  const auto [driven, driven_why] = run(false);
  EXPECT_EQ(driven, GoalStatus::kActive) << driven_why;
  const auto [jumped, jumped_why] = run(true);
  EXPECT_EQ(jumped, GoalStatus::kNoPath);
  EXPECT_EQ(no_path_cause(jumped_why), NoPathCause::kStartCutOff) << jumped_why;
}

}  // namespace
}  // namespace rgnav::planner
