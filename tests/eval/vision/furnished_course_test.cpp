// The furnished courses of the vision's course bench (furnished_course.h): every drawn course is
// passable in 3D (some path keeps the clearance from every footprint), its furniture does not
// overlap, its targets keep out of the footprints, the start and goal are free; the laser's plane
// meets table legs and chair columns only (the tops, seats and shelves are above it); and enough
// courses put furniture across the straight way that driving by the laser alone can fail.
#include "furnished_course.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/scene.h"

namespace rgnav::bench {
namespace {

double to_box(const Eigen::Vector2d& p, const sim::Box& b)
{
  const Eigen::Vector2d l = sim::rotate(p - b.center, -b.yaw);
  return (l.cwiseAbs() - 0.5 * b.size).cwiseMax(0.0).norm();
}

TEST(FurnishedCourse, CoursesArePassableTidyAndTheLaserSeesOnlyLegsAndColumns)
{
  std::mt19937 rng(5);
  FurnishedCourseOptions o;
  int across_the_way = 0;
  const int n = 25;
  for (int k = 0; k < n; ++k) {
    const FurnishedCourse c = draw_furnished_course(rng, o);
    const sim::World& w = c.course.world;
    ASSERT_GE(c.tables, 1);
    ASSERT_FALSE(c.course.targets.empty());
    sim::World solid;
    solid.walls = w.walls;
    solid.boxes = c.footprints;
    const Eigen::Vector2d start(0, 0), goal = c.course.targets.back().translation();
    EXPECT_TRUE(passable(solid, start, goal, o.clearance)) << "course " << k;
    for (const auto& t : c.course.targets)
      for (const auto& fp : c.footprints) EXPECT_GT(to_box(t.translation(), fp), o.clearance) << "course " << k << " " << fp.name;
    for (size_t i = 0; i < c.footprints.size(); ++i)
      for (size_t j = i + 1; j < c.footprints.size(); ++j)
        for (const auto& corner : c.footprints[i].corners())
          EXPECT_GT(to_box(corner, c.footprints[j]), 0.0) << c.footprints[i].name << " in " << c.footprints[j].name;
    // The laser's plane (0.4 m) holds table legs and chair columns, nothing else of the furniture.
    const sim::Scene scene(w);
    for (const auto& s : scene.segments()) {
      if (!(s.z_min <= 0.4f && s.z_max >= 0.4f)) continue;
      const std::string& owner = scene.owner_names()[static_cast<size_t>(s.owner)];
      if (owner.rfind("wall", 0) == 0) continue;
      EXPECT_TRUE(owner.find(".leg") != std::string::npos || owner.find(".column") != std::string::npos) << owner;
    }
    // Furniture across the straight way to the goal (within the robot's radius of the line).
    bool across = false;
    for (const auto& fp : c.footprints)
      for (double s = 0; s <= 1.0; s += 0.01) across = across || to_box(start + s * (goal - start), fp) < 0.26;
    across_the_way += across ? 1 : 0;
  }
  EXPECT_GE(across_the_way, n / 2);
}

TEST(FurnishedCourse, APedestalChairIsASeatAndABackOverAThinColumn)
{
  const auto parts = pedestal_chair("c", {1.0, 2.0}, M_PI / 2);
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_LE(parts[0].size.maxCoeff(), 0.1);     // the column: all the laser can see
  EXPECT_GT(parts[1].z_min, 0.4);               // the seat is above the laser's plane
  EXPECT_NEAR(parts[2].center.y(), 1.8, 1e-9);  // facing +y, the back is behind (-y)
}

}  // namespace
}  // namespace rgnav::bench
