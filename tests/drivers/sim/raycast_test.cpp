#include <gtest/gtest.h>

#include <cmath>

#include "sim/lms2xx_model.h"
#include "sim/scene.h"

namespace rgnav::sim {
namespace {

Wall wall(Vec2 a, Vec2 b, double z_min = 0.0, double z_max = 2.5)
{
  Wall w;
  w.a = a;
  w.b = b;
  w.z_min = z_min;
  w.z_max = z_max;
  return w;
}

Lms2xxOptions exact_laser(int beams = 181, int mode = 8)
{
  Lms2xxOptions o;
  o.beams = beams;
  o.range_mode_m = mode;
  o.noise_sigma = 0.0;
  o.mount_x = 0.0;
  return o;
}

const std::vector<uint8_t> kNoDoors;

TEST(RayCast, DistanceToAWallAtKnownAngles)
{
  World w;
  w.walls.push_back(wall({3, -20}, {3, 20}));  // the line x = 3
  const Scene scene(w);
  for (double deg : {-80.0, -45.0, -10.0, 0.0, 1.0, 30.0, 60.0, 75.0}) {
    const double a = deg * M_PI / 180.0;
    const RayHit hit = scene.cast({0, 0}, {std::cos(a), std::sin(a)}, 100.0, {0.4, 0.4}, kNoDoors);
    EXPECT_NEAR(hit.range, 3.0 / std::cos(a), 1e-9) << deg;
  }
  // Away from the wall: nothing.
  EXPECT_TRUE(std::isinf(scene.cast({0, 0}, {-1, 0}, 100.0, {0.4, 0.4}, kNoDoors).range));
}

TEST(RayCast, ScanBeamsMatchGeometryWithinQuantisation)
{
  World w;
  w.walls.push_back(wall({2, -10}, {2, 10}));  // in front, x = 2
  w.walls.push_back(wall({-10, 1.5}, {10, 1.5}));  // left, y = 1.5
  const Scene scene(w);
  Lms2xxModel laser(exact_laser(), Rng(1));
  const sensors::LaserScan s = laser.measure(scene, kNoDoors, {}, {0, 0, 0}, 123, 1);
  ASSERT_EQ(s.ranges.size(), 181u);
  EXPECT_NEAR(s.angle_increment, M_PI / 180.0, 1e-12);
  EXPECT_NEAR(s.angle_min, -M_PI / 2, 1e-12);
  for (int i = 0; i < 181; ++i) {
    const double a = -M_PI / 2 + i * M_PI / 180.0;
    double expect = 8.183;  // no return
    if (std::cos(a) > 1e-9) expect = std::min(expect, 2.0 / std::cos(a));
    if (std::sin(a) > 1e-9) expect = std::min(expect, 1.5 / std::sin(a));
    expect = std::min(expect, 8.183);
    EXPECT_NEAR(s.ranges[static_cast<size_t>(i)], expect, 0.0005 + 1e-6) << "beam " << i;
  }
  // Beam 0 looks right (-y): no wall there -> max range.
  EXPECT_FLOAT_EQ(s.ranges[0], static_cast<float>(s.range_max));
}

TEST(RayCast, TableLegsSeenTabletopNot)
{
  World w;
  Table t;
  t.center = {2.0, 0.0};
  t.size = {1.2, 0.8};
  t.leg_size = 0.05;
  w.tables.push_back(t);
  w.walls.push_back(wall({5, -5}, {5, 5}));
  const Scene scene(w);
  // Straight through the middle, between the legs: the wall behind, not the top.
  EXPECT_NEAR(scene.cast({0, 0}, {1, 0}, 20, {0.4, 0.4}, kNoDoors).range, 5.0, 1e-9);
  // The same ray at the tabletop's height hits its edge at x = 2 - 0.6.
  EXPECT_NEAR(scene.cast({0, 0}, {1, 0}, 20, {0.71, 0.71}, kNoDoors).range, 1.4, 1e-9);
  // Aimed at a leg centre (x = 2 - 0.6 + 0.05, y = 0.4 - 0.05): hits its face at x = 1.375.
  const Vec2 leg(1.45, 0.35);
  const RayHit h = scene.cast({0, 0.35}, {1, 0}, 20, {0.4, 0.4}, kNoDoors);
  EXPECT_NEAR(h.range, leg.x() - 0.025, 1e-9);
  // The robot body (up to 1.2 m) collides with the top even between the legs.
  const Clearance c = scene.clearance({1.5, 0.0}, 1.0, {0.02, 1.2}, kNoDoors);
  EXPECT_NEAR(c.distance, 0.1, 1e-9);  // inside the top: 0.1 m from its edge
  const Clearance below = scene.clearance({1.5, 0.0}, 0.2, {0.4, 0.4}, kNoDoors);
  EXPECT_TRUE(std::isinf(below.distance));
}

TEST(RayCast, OnlyObstaclesSpanningTheScanPlane)
{
  World w;
  w.walls.push_back(wall({1, -1}, {1, 1}, 0.0, 0.3));   // low: under the beam
  w.walls.push_back(wall({2, -1}, {2, 1}, 0.5, 2.0));   // high: above the beam
  w.walls.push_back(wall({3, -1}, {3, 1}, 0.0, 2.0));   // seen
  const Scene scene(w);
  EXPECT_NEAR(scene.cast({0, 0}, {1, 0}, 20, {0.4, 0.4}, kNoDoors).range, 3.0, 1e-9);
}

TEST(RayCast, DoorsBlockOnlyWhenClosed)
{
  World w;
  Door d;
  d.hinge = {2, -0.5};
  d.latch = {2, 0.5};
  w.doors.push_back(d);
  w.walls.push_back(wall({4, -2}, {4, 2}));
  const Scene scene(w);
  EXPECT_NEAR(scene.cast({0, 0}, {1, 0}, 20, {0.4, 0.4}, {1}).range, 4.0, 1e-9);
  EXPECT_NEAR(scene.cast({0, 0}, {1, 0}, 20, {0.4, 0.4}, {0}).range, 2.0, 1e-9);
}

TEST(RayCast, PeopleAreSeenAsCircles)
{
  World w;
  w.walls.push_back(wall({6, -5}, {6, 5}));
  const Scene scene(w);
  Lms2xxModel laser(exact_laser(), Rng(1));
  const auto r = laser.true_ranges(scene, kNoDoors, {{{3.0, 0.0}, 0.25}}, {0, 0, 0});
  EXPECT_NEAR(r[90], 2.75, 1e-9);
  EXPECT_NEAR(r[60], 6.0 / std::cos(30 * M_PI / 180), 1e-9);
}

TEST(RayCast, RangeModesAndBeamCounts)
{
  World w;
  w.walls.push_back(wall({20, -50}, {20, 50}));
  w.walls.push_back(wall({0.0, 3.21234}, {1.0, 3.21234}));
  const Scene scene(w);
  Lms2xxModel mm(exact_laser(361, 8), Rng(1));
  const sensors::LaserScan a = mm.measure(scene, kNoDoors, {}, {0, 0, 0}, 0, 1);
  ASSERT_EQ(a.ranges.size(), 361u);
  EXPECT_FLOAT_EQ(a.ranges[180], static_cast<float>(8.183));  // 20 m is beyond the 8 m mode
  EXPECT_FLOAT_EQ(a.ranges[360], 3.212f);                      // mm resolution
  EXPECT_NEAR(a.scan_time, 1.0 / 37.5, 1e-12);
  Lms2xxModel cm(exact_laser(181, 80), Rng(1));
  const sensors::LaserScan b = cm.measure(scene, kNoDoors, {}, {0, 0, 0}, 0, 1);
  EXPECT_FLOAT_EQ(b.ranges[90], 20.0f);
  EXPECT_FLOAT_EQ(b.ranges[180], 3.21f);                       // cm resolution
  EXPECT_NEAR(b.scan_time, 1.0 / 75.0, 1e-12);
}

TEST(RayCast, NoiseHasTheConfiguredSpread)
{
  World w;
  w.walls.push_back(wall({4, -50}, {4, 50}));
  const Scene scene(w);
  Lms2xxOptions o = exact_laser();
  o.noise_sigma = 0.02;
  Lms2xxModel laser(o, Rng(99));
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int k = 0; k < 200; ++k) {
    const sensors::LaserScan s = laser.measure(scene, kNoDoors, {}, {0, 0, 0}, 0, k + 1);
    const double e = s.ranges[90] - 4.0;
    sum += e;
    sum2 += e * e;
    ++n;
  }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 0.006);
  EXPECT_NEAR(sd, 0.02, 0.005);
}

}  // namespace
}  // namespace rgnav::sim
