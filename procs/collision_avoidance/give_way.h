// Giving way to a person in a doorway or a narrow hallway (diss. 5.5.3's fallback layer, the
// situation it leaves open): the robot and a person coming the other way cannot pass each
// other there; the person stops at their personal space and waits for the robot to clear
// their way, and the robot, whose way leads through where the person stands, waits for them.
//
// What breaks it is the robot leaving the person's way. Not back along it: that is where the
// person wants to walk, so a person who waits walks up again, stops again, and the robot backs
// up again (a deadlock in slow motion). Sideways: the robot finds the nearest place it can
// reach that lies out of the person's predicted path (the straight line on from where they are
// along the way they walk, as wide as a person passing), goes there, turns to watch the path,
// and waits until nobody is left to pass (someone_to_pass) before it goes on. In a hallway
// that place lies beyond its mouth, into the room behind the robot.
//
// Better not to meet in there at all (one_lane_between): someone coming toward the robot
// through a stretch too narrow for both, who would be in it before the robot is out, gets the
// way before the robot goes in; the robot already in it while they are not yet goes on through.
//
// Where no such place can be found (boxed in, or nothing known around), the old way is the
// last resort: drive back along the freest line away from the target (choose_give_way).
#pragma once

#include <optional>
#include <vector>

#include "collision_avoidance/local_map.h"

namespace rgnav::collision_avoidance {

// A person's predicted path: from where they stand, straight on along the way they walk (no
// end: a yield point just past where a path of some length ends would stand where they walk on).
struct PersonPath
{
  Eigen::Vector2d from = Eigen::Vector2d::Zero();       // odom frame
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // unit
  // Distance from p to the path's centre line (a ray: behind `from`, the distance to it).
  double distance(const Eigen::Vector2d& p) const;
  // How far along the path p lies (negative: behind where they stand).
  double along(const Eigen::Vector2d& p) const { return (p - from).dot(direction); }
};

struct YieldOptions
{
  double path_half_width = 0.45; // [m] a person passing: their radius and some sway
  double extra = 0.50;           // [m] the yield point this much beyond clearance + half width from the path
  double spot_margin = 0.05;     // [m] and this much more room around it than the clearance
  // [m] the way there keeps this beyond the clearance where it can (the scans on the way add
  // what was not seen yet: a way grazing a door frame is blocked by the next scan of it)
  double way_margin = 0.05;
  double max_travel = 8.0;       // [m] reachable within this (path length): a hallway's length and its mouth
  double person_keep = 0.30;     // [m] the way there keeps this much beyond the clearance from where they stand
  double in_path_cost = 3.0;     // cost factor of cells on the person's path: leave it at once
  // Cost factor of steps down the person's path (the way they walk): beside where they come from
  // (next to a door) the robot is behind them once they have passed; farther down, their path
  // may bend toward it (toward the place they walk to), and they stop again.
  double downstream_cost = 2.0;
  double shadow_cost = 3.0;      // cost factor of cells in view but not seen (behind what the scans hit)
  double cell = 0.10;            // [m] search grid
  // Waiting there (someone_to_pass): movers this close to the path's centre line count ...
  double watch_half_width = 0.9; // [m]
  double watch_behind = 3.0;     // [m] ... from this far behind where the person stood to the robot
};

struct YieldPoint
{
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  // odom frame
  std::vector<Eigen::Vector2d> corners;             // the way there from the robot (excluded), ending at `point`
  double travel = 0.0;    // [m] along the corners
  double off_path = 0.0;  // [m] the point's distance from the path's centre line
};

// The cheapest place to reach from `robot` that lies clear of `path` (clearance + half width +
// extra) with room around it: a search over the local map's grid (local_grid.h) from the robot,
// through space in view (seen, or in the shadow of what was seen, at a higher cost; never out of
// every view, but for the robot's own surroundings), never nearer the person than clearance +
// person_keep, steps on the person's path and down it costing more. Nothing: no such place
// within max_travel.
std::optional<YieldPoint> choose_yield_point(const LocalMap& map, const Eigen::Vector2d& robot, const PersonPath& path,
                                             double clearance, const YieldOptions& options);

// A way from `robot` to `to` (corners, `to` last) by the same search, ending where `to` lies;
// nothing if there is none within twice max_travel, or `to` is not where the robot fits. The
// way back to where the robot left its way, once the person has passed.
std::optional<std::vector<Eigen::Vector2d>> way_to(const LocalMap& map, const Eigen::Vector2d& robot,
                                                   const Eigen::Vector2d& to, double clearance, const YieldOptions& options);

// Whether someone is still to pass the robot waiting at `robot` beside `path`: a tracked mover
// (not walking away along the path: someone who turned back leaves the way free), or a mover that
// stopped and still stands there, within watch_half_width of the path's centre line between
// watch_behind behind its start and the robot's place along it.
enum class ToPass
{
  kNobody,
  kWalking,   // someone walks there (toward the robot, or not yet known where)
  kStanding,  // only someone who stopped there (maybe waiting for the robot in turn)
};
ToPass someone_to_pass(const LocalMap& map, const PersonPath& path, const Eigen::Vector2d& robot,
                       const YieldOptions& options);

// Where the robot at `robot` and a person at `person` coming toward it cannot pass each other: the
// stretch of the straight line between them (up to `person_radius` short of the person) where the
// space across it is narrower than `width` (a doorway, a narrow hallway). Across it: the nearest
// obstacle points to either side within kOneLaneSlab along the line; the laser's points on a
// wall seen at a grazing angle lie farther apart, so a side without any there takes the wider
// of what it has within kOneLaneBridge either way. The person's own points (within
// person_radius + 0.15 m of them) and where movers are only predicted to be are left out.
// Nothing known to one side: room to pass. Nothing: they can pass each other all the way.
struct OneLane
{
  double begin = 0.0;   // [m] along the line from the robot (0: the robot is in it)
  double end = 0.0;     // [m] (of the last, where there are several)
  double length = 0.0;  // [m] of the line looked along (to person_radius short of the person)
};
constexpr double kOneLaneSlab = 0.15;  // [m] either side of a place along the line
constexpr double kOneLaneBridge = 1.0; // [m] a side with no point there takes what it has this near either way
std::optional<OneLane> one_lane_between(const LocalMap& map, const Eigen::Vector2d& robot, const Eigen::Vector2d& person,
                                        double width, double person_radius);
// The same measure along the straight line from `from` to `to`, leaving out the points within
// `exclude_radius` of `exclude` (someone's own).
std::optional<OneLane> one_lane_along(const LocalMap& map, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                                      double width, const Eigen::Vector2d& exclude, double exclude_radius);

// The last resort. Among headings within `spread` of straight back (`away`: odom frame, from
// the target), the straight line from the robot that stays free (the planner's footprint
// check) for longest wins, weighted by how directly it leads back.
struct GiveWayOptions
{
  double length = 1.0;       // [m] how far to drive back at most
  double min_length = 0.3;   // [m] shorter free lines do not count
  double spread = 1.57;      // [rad] headings up to this far either side of straight back
  int headings = 9;          // tried over [-spread, spread]
  YieldOptions yield;        // first: out of the person's path sideways
};

struct GiveWay
{
  double heading = 0.0;  // [rad] odom frame
  double length = 0.0;   // [m] free along it
};

// clearance: robot radius + safety margin; step: the footprint check's step. Nothing if no
// line is free for min_length.
std::optional<GiveWay> choose_give_way(const LocalMap& map, const Eigen::Vector2d& from, double away, double clearance,
                                       double step, const GiveWayOptions& options);

}  // namespace rgnav::collision_avoidance
