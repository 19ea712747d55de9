// Generated obstacle courses in a furnished room for the vision's course bench: a walled room
// with tables (a top at 0.72-0.78 m on four legs: the laser at 0.4 m sees only the legs, and a
// robot fits between two of them), pedestal chairs (a seat and backrest over one thin column)
// and shelves fixed to the walls at 0.55-0.95 m (nothing at the laser's height), the robot
// starting at one end and its goal at the other. The furniture is drawn around the straight way
// to the goal, so driving by the laser alone may go under a table top or a seat; a course is kept
// only when some path keeps the robot's clearance from every solid in its height band (the
// furniture's whole footprints), so avoiding them all can reach the goal.
#pragma once

#include <random>
#include <vector>

#include "obstacle_course.h"
#include "sim/world.h"

namespace rgnav::bench {

struct FurnishedCourseOptions
{
  double clearance = 0.36;        // [m] robot radius + safety margin the furniture must leave on some path
  double target_spacing = 1.0;    // [m] targets along the straight way; those in a footprint's clearance left out
};

struct FurnishedCourse
{
  Course course;
  int tables = 0, chairs = 0, shelves = 0;
  int redrawn = 0;                // impassable courses drawn and discarded before this one
  // The furniture's footprints as boxes (what the robot must keep out of in 3D).
  std::vector<sim::Box> footprints;
};

FurnishedCourse draw_furnished_course(std::mt19937& rng, const FurnishedCourseOptions& options);

// The parts of a pedestal chair at `center` facing `yaw` (seat 0.45 m square over a 6 cm column,
// backrest on the side away from `yaw`): boxes for World::boxes.
std::vector<sim::Box> pedestal_chair(const std::string& name, const Eigen::Vector2d& center, double yaw);

}  // namespace rgnav::bench
