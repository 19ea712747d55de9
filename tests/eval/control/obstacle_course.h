// Randomised obstacle courses for control_bench: a corridor 3 m wide and 14 m long with
// boxes and people walking across it; targets 1 m apart along its centre. A course is
// physically consistent (people walk around furniture, not through it) and passable: some
// path from the start to the goal keeps the robot's clearance from walls and boxes (a course
// that is not is drawn again, and counted). Whether the robot times its way past the people
// is what the bench measures.
#pragma once

#include <random>
#include <vector>

#include "geometry/pose2.h"
#include "sim/world.h"

namespace rgnav::bench {

struct Course
{
  sim::World world;
  std::vector<geometry::Pose2> targets;  // odom frame == world frame (start pose at the origin)
};

struct CourseDraw
{
  Course course;
  int redrawn = 0;  // impassable or inconsistent courses drawn and discarded before this one
};

// `clearance`: robot radius plus safety margin the static obstacles must leave on some path.
// `personal_space`: the people's (world.h Person); the course geometry does not depend on it.
CourseDraw draw_course(std::mt19937& rng, double clearance, double personal_space);

// Whether a disc of radius `clearance` can move from `from` to `to` among the world's walls
// and boxes (grid search at `cell`, conservative by half a cell diagonal).
bool passable(const sim::World& world, const Eigen::Vector2d& from, const Eigen::Vector2d& to, double clearance,
              double cell = 0.05);

}  // namespace rgnav::bench
