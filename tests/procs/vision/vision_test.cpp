// The vision library (procs/vision) without a bus: depth from a synthetic textured plane,
// points through the head pose into the base frame, a table top at 0.7 m as an occupied column
// over a free floor, the laser fused in its layer, drop-offs, and the map's bounded size on a
// long drive.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "synthetic_stereo.h"
#include "vision/dense_stereo.h"
#include "vision/obstacle_map.h"
#include "vision/octree_trim.h"
#include "vision/rectifier.h"
#include "vision/vision_pipeline.h"

namespace rgnav::vision {
namespace {

using geometry::Pose2;

constexpr double kFocal = 500.0;
constexpr double kBaseline = 0.12;
const cv::Size kSize(640, 480);

double median(std::vector<double> v)
{
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

TEST(DenseStereo, PlaneAtKnownDepth)
{
  for (const double depth : {1.0, 2.0, 3.0}) {
    const int d = static_cast<int>(std::lround(kFocal * kBaseline / depth));
    const double z = kFocal * kBaseline / d;   // the depth the whole-pixel shift stands for
    const auto pair = synthetic::plane_pair(kSize, d, 7);
    const Rectifier rect(ideal_rig(kSize, kFocal, kBaseline), 0.0);
    ASSERT_TRUE(rect.identity());
    DisparityOptions o;
    o.num_disparities = 80;
    const DenseStereo stereo(o);
    PointOptions po;
    po.stride = 4;
    const auto points = disparity_to_points(stereo.disparity(pair.left, pair.right), rect.camera(), po);
    ASSERT_GT(points.size(), 5000u) << "depth " << depth;
    std::vector<double> zs;
    int near = 0;
    for (const auto& p : points) {
      zs.push_back(p.z());
      if (std::abs(p.z() - z) < 0.03 * z) ++near;
    }
    EXPECT_NEAR(median(zs), z, 0.01 * z) << "depth " << depth;
    EXPECT_GT(near, static_cast<int>(0.95 * points.size())) << "depth " << depth;
  }
}

TEST(DenseStereo, DownscaledMatchingKeepsDepth)
{
  const double z = kFocal * kBaseline / 40;
  const auto pair = synthetic::plane_pair(kSize, 40, 3);
  const Rectifier rect(ideal_rig(kSize, kFocal, kBaseline), 0.0);
  DisparityOptions o;
  o.downscale = 2;
  o.num_disparities = 48;
  const DenseStereo stereo(o);
  const auto points = disparity_to_points(stereo.disparity(pair.left, pair.right), rect.camera().scaled_down(2), {});
  ASSERT_GT(points.size(), 5000u);
  std::vector<double> zs;
  for (const auto& p : points) zs.push_back(p.z());
  EXPECT_NEAR(median(zs), z, 0.02 * z);
}

TEST(Rectifier, RotatedRigIsRectified)
{
  // A right camera turned by 1 degree: rectification takes it out, and a point projects to the
  // same row in both rectified images.
  StereoRig rig = ideal_rig(kSize, kFocal, kBaseline);
  cv::Mat rvec = (cv::Mat_<double>(3, 1) << 0.0, 0.0175, 0.0);
  cv::Rodrigues(rvec, rig.R);
  const Rectifier rect(rig, 0.0);
  EXPECT_FALSE(rect.identity());
  EXPECT_NEAR(rect.camera().baseline, kBaseline, 1e-6);
  EXPECT_GT(rect.camera().focal, 0.8 * kFocal);
  cv::Mat img(kSize, CV_8UC1, cv::Scalar(0));
  cv::Mat l, r;
  rect.rectify(img, img, &l, &r);
  EXPECT_EQ(l.size(), kSize);
  EXPECT_EQ(l.type(), CV_8UC1);
}

TEST(VisionPipeline, PointsReachTheBaseFrameThroughTheHead)
{
  StereoRig rig = ideal_rig(kSize, kFocal, kBaseline);
  rig.base_from_head.translation() = Eigen::Vector3d(0.05, 0.0, 1.25);
  VisionOptions o;
  o.disparity.num_disparities = 64;
  o.map.max_range = 6.0;
  VisionPipeline vp(rig, o);
  // A wall 2 m ahead of the camera, the head panned 90 degrees left: the wall is at y = +2.
  const int d = 30;
  const double z = kFocal * kBaseline / d;
  const auto pair = synthetic::plane_pair(kSize, d, 11);
  StereoFrame f;
  f.utime = 1;
  f.left = pair.left;
  f.right = pair.right;
  f.pan = M_PI / 2;
  const auto r = vp.process(f);
  ASSERT_GT(r.points, 5000u);
  // Occupied cells lie on the line y = z (+ camera offset), spread along x.
  int wall = 0, elsewhere = 0;
  for (int y = 0; y < r.grid.height; ++y)
    for (int x = 0; x < r.grid.width; ++x) {
      if (r.grid.at(x, y) < 50) continue;
      const double wy = r.grid.odom_from_grid.y() + (y + 0.5) * r.grid.resolution;
      if (std::abs(wy - z) < 0.1) ++wall;
      else ++elsewhere;
    }
  EXPECT_GT(wall, 20);
  EXPECT_LT(elsewhere, wall / 10);
}

// Points a camera at (0, 0, 1.25) sees: the floor from x0 to x1 and a table top (0.7 m) over
// [tx0, tx1] x [-0.4, 0.4], both as dense grids of points.
std::vector<Eigen::Vector3f> table_scene(double tx0, double tx1)
{
  std::vector<Eigen::Vector3f> pts;
  for (double x = 0.6; x < 3.5; x += 0.02)
    for (double y = -1.0; y <= 1.0; y += 0.02) {
      const bool under_table = x >= tx0 && x <= tx1 && std::abs(y) <= 0.4;
      // The camera sees the top, not the floor beneath it (nor the floor it hides behind).
      const bool hidden = x > tx1 && x < tx1 + (tx1 * 0.7 / (1.25 - 0.7)) && std::abs(y) <= 0.4;
      if (!under_table && !hidden) pts.emplace_back(x, y, 0.0);
    }
  for (double x = tx0; x <= tx1; x += 0.02)
    for (double y = -0.4; y <= 0.4; y += 0.02) pts.emplace_back(x, y, 0.7);
  return pts;
}

double cell_value(const ObstacleGrid& g, double x, double y)
{
  int cx, cy;
  if (!g.cell_of({x, y}, &cx, &cy)) return -2;
  return g.at(cx, cy);
}

TEST(ObstacleMap, TableTopIsAnObstacleAndTheFloorStaysFree)
{
  ObstacleMapOptions o;
  ObstacleMap map(o);
  const Pose2 robot(0, 0, 0);
  for (int i = 0; i < 3; ++i) map.insert_stereo(table_scene(1.5, 2.0), {0, 0, 1.25}, robot);
  const ObstacleGrid g = map.project(robot, 1);
  EXPECT_GE(cell_value(g, 1.75, 0.0), 50);   // table top
  EXPECT_GE(cell_value(g, 1.55, 0.35), 50);
  EXPECT_EQ(cell_value(g, 1.0, 0.0), 0);     // floor in front of it
  EXPECT_EQ(cell_value(g, 2.5, 0.8), 0);     // floor beside and beyond it
  EXPECT_EQ(cell_value(g, -2.0, 0.0), -1);   // behind the camera: never seen
  // Band without the table's height (a robot that fits under it): the table is not an obstacle.
  o.max_height = 0.6;
  ObstacleMap low(o);
  for (int i = 0; i < 3; ++i) low.insert_stereo(table_scene(1.5, 2.0), {0, 0, 1.25}, robot);
  EXPECT_LT(cell_value(low.project(robot, 1), 1.75, 0.0), 50);
}

constexpr int64_t kS = 1'000'000;

// The camera of the half-scale matching image (f = 250 px, 320x240) 1.25 m up, looking ahead.
StereoView ahead_view()
{
  StereoView v;
  v.base_from_camera = optical_from_forward();
  v.base_from_camera.translation() = Eigen::Vector3d(0, 0, 1.25);
  v.focal = 250;
  v.cx = 160;
  v.cy = 120;
  v.width = 320;
  v.height = 240;
  v.min_depth = 0.47;
  v.max_depth = 2.5;
  return v;
}

// Points of an upright body: x in [x0, x1] at y, heights z0..z1 (its side facing the camera).
std::vector<Eigen::Vector3f> body(double x0, double x1, double y, double z0, double z1)
{
  std::vector<Eigen::Vector3f> pts;
  for (double z = z0; z <= z1 + 1e-9; z += 0.02)
    for (double x = x0; x <= x1 + 1e-9; x += 0.02) pts.emplace_back(x, y, z);
  return pts;
}

// The points of `pts` the camera of `view` sees (in the image, within its depths).
std::vector<Eigen::Vector3f> seen_by(const std::vector<Eigen::Vector3f>& pts, const StereoView& view)
{
  std::vector<Eigen::Vector3f> out;
  const Eigen::Isometry3d camera_from_base = view.base_from_camera.inverse();
  for (const auto& p : pts) {
    const Eigen::Vector3d c = camera_from_base * p.cast<double>();
    if (c.z() < view.min_depth) continue;
    const double u = view.focal * c.x() / c.z() + view.cx, v = view.focal * c.y() / c.z() + view.cy;
    if (u >= 0 && v >= 0 && u < view.width && v < view.height) out.push_back(p);
  }
  return out;
}

// Points of a level board (a chair seat) over [x0, x1] x [y0, y1] at height z.
std::vector<Eigen::Vector3f> board(double x0, double x1, double y0, double y1, double z)
{
  std::vector<Eigen::Vector3f> pts;
  for (double x = x0; x <= x1 + 1e-9; x += 0.02)
    for (double y = y0; y <= y1 + 1e-9; y += 0.02) pts.emplace_back(x, y, z);
  return pts;
}

// Someone seen once 1.2 m to the left, and a chair seat 0.5 m ahead (0.47 m up: below the level
// camera's view from 1.25 m), then 40 s of frames looking ahead at a table: neither is in view
// again, so neither is forgotten (the time-only rule, forget_after_s 30, forgot both: a chair
// seat the robot then drove into). The table, seen all along, stays.
TEST(ObstacleMap, CellsOutOfViewOrTooNearAreKept)
{
  const Pose2 robot(0, 0, 0);
  const StereoView view = ahead_view();
  ObstacleMapOptions o;
  o.forget_in_view_after = 3.0;
  ObstacleMap map(o);
  const int64_t t0 = 100 * kS;
  auto first = body(-0.1, 0.1, 1.2, 0.2, 1.4);
  const auto seat = board(0.45, 0.65, -0.2, 0.2, 0.47);
  first.insert(first.end(), seat.begin(), seat.end());
  for (int i = 0; i < 3; ++i) map.insert_stereo(first, {0, 0, 1.25}, robot, 0.0, t0 + i * kS / 10, &view);
  ASSERT_GE(cell_value(map.project(robot, 1), 0.0, 1.2), 50);
  ASSERT_GE(cell_value(map.project(robot, 1), 0.55, 0.0), 50);
  const auto ahead = seen_by(table_scene(1.5, 2.0), view);
  for (int i = 1; i <= 400; ++i) map.insert_stereo(ahead, {0, 0, 1.25}, robot, 0.0, t0 + i * kS / 10, &view);
  const ObstacleGrid g = map.project(robot, 2);
  EXPECT_GE(cell_value(g, 1.75, 0.0), 50);   // seen all along
  EXPECT_GE(cell_value(g, 0.0, 1.2), 50);    // beside: out of view
  EXPECT_GE(cell_value(g, 0.55, 0.0), 50);   // below the view, nearer than it reaches
  EXPECT_EQ(map.forgotten(), 0);
}

// A body 2 m ahead, then frames without a point on it and no ray through it (it left, and what
// is behind gives no disparity): forgotten after forget_in_view_after of looking at it. Not
// while a nearer wall hides it, nor without the camera's view, nor with the rule off.
TEST(ObstacleMap, CellsInViewWithoutPointsAreForgottenUnlessHidden)
{
  const Pose2 robot(0, 0, 0);
  const StereoView view = ahead_view();
  // Floor far to the sides only: no ray crosses the body's place.
  const auto floor_aside = board(1.0, 2.5, 1.0, 1.5, 0.0);
  std::vector<Eigen::Vector3f> wall;   // a board across the view 1.2 m ahead
  for (double y = -0.6; y <= 0.6 + 1e-9; y += 0.02)
    for (double z = 0.1; z <= 1.5 + 1e-9; z += 0.02) wall.emplace_back(1.2, y, z);
  struct Case
  {
    const char* name;
    double forget_after;
    bool hidden;
    bool with_view;
    bool forgotten;
  };
  for (const Case& c : {Case{"in view", 3.0, false, true, true}, Case{"hidden", 3.0, true, true, false},
                        Case{"no view", 3.0, false, false, false}, Case{"rule off", 0.0, false, true, false}}) {
    ObstacleMapOptions o;
    o.forget_in_view_after = c.forget_after;
    ObstacleMap map(o);
    const StereoView* v = c.with_view ? &view : nullptr;
    const int64_t t0 = 100 * kS;
    for (int i = 0; i < 3; ++i) map.insert_stereo(body(1.9, 2.1, 0.0, 0.5, 1.0), {0, 0, 1.25}, robot, 0.0, t0 + i * kS / 10, v);
    ASSERT_GE(cell_value(map.project(robot, 1), 2.0, 0.0), 50) << c.name;
    // 2 s: not yet.
    int i = 3;
    for (; i <= 20; ++i) map.insert_stereo(c.hidden ? wall : floor_aside, {0, 0, 1.25}, robot, 0.0, t0 + i * kS / 10, v);
    EXPECT_GE(cell_value(map.project(robot, 2), 2.0, 0.0), 50) << c.name;
    for (; i <= 60; ++i) map.insert_stereo(c.hidden ? wall : floor_aside, {0, 0, 1.25}, robot, 0.0, t0 + i * kS / 10, v);
    const double after = cell_value(map.project(robot, 3), 2.0, 0.0);
    if (c.forgotten) {
      EXPECT_LT(after, 50) << c.name;
      EXPECT_GT(map.forgotten(), 0) << c.name;
    } else {
      EXPECT_GE(after, 50) << c.name;
      EXPECT_EQ(map.forgotten(), 0) << c.name;
    }
  }
}

// Seen free: rays to a wall behind the place where the body stood pass through its cells and
// clear them (OctoMap's free space), with no time rule at all.
TEST(ObstacleMap, CellsSeenFreeAreCleared)
{
  const Pose2 robot(0, 0, 0);
  ObstacleMapOptions o;
  o.forget_in_view_after = 0.0;
  ObstacleMap map(o);
  for (int i = 0; i < 3; ++i) map.insert_stereo(body(1.5, 1.7, 0.0, 0.6, 1.0), {0, 0, 1.25}, robot);
  ASSERT_GE(cell_value(map.project(robot, 1), 1.6, 0.0), 50);
  std::vector<Eigen::Vector3f> wall;
  for (double y = -0.5; y <= 0.5 + 1e-9; y += 0.02)
    for (double z = 0.1; z <= 1.4 + 1e-9; z += 0.02) wall.emplace_back(2.4, y, z);   // rays cross the body's place
  for (int i = 0; i < 15; ++i) map.insert_stereo(wall, {0, 0, 1.25}, robot);
  EXPECT_LT(cell_value(map.project(robot, 2), 1.6, 0.0), 50);
  EXPECT_GE(cell_value(map.project(robot, 2), 2.4, 0.0), 50);
}

// A scan from the laser at the base's centre 0.4 m up, all around: `hits` (bearing [rad] ->
// range) and no return (range_max) elsewhere.
sensors::LaserScan scan_around(const std::vector<std::pair<double, double>>& hits)
{
  sensors::LaserScan s;
  s.angle_min = -M_PI;
  s.angle_increment = M_PI / 360;
  s.range_min = 0.05;
  s.range_max = 30.0;
  for (int i = 0; i < 720; ++i) {
    double r = s.range_max;
    for (const auto& [bearing, range] : hits)
      if (std::abs(std::remainder(s.bearing(i) - bearing, 2 * M_PI)) < 0.09) r = range;
    s.ranges.push_back(static_cast<float>(r));
  }
  return s;
}

// Someone beside the robot, out of view, whom stereo saw once and the laser sees (their legs):
// when the laser sees through that place, stereo's cells of them go too. A chair seat whose
// column the laser never saw occupied (it passes beneath) stays. Without the rule the person
// stays an obstacle for as long as the camera does not look there.
TEST(ObstacleMap, LaserSeeingSomeoneGoneClearsWhatStereoSawOfThem)
{
  const Pose2 robot(0, 0, 0);
  const Pose2 base_from_laser(0, 0, 0);
  const StereoView view = ahead_view();
  // The person's near side at y = 1.2 (a body 0.2 m wide), the seat ahead below the view.
  auto seen = body(-0.1, 0.1, 1.2, 0.1, 1.4);
  const auto seat = board(0.45, 0.65, -0.2, 0.2, 0.47);
  seen.insert(seen.end(), seat.begin(), seat.end());
  const auto present = scan_around({{M_PI / 2, 1.2}});
  const auto gone = scan_around({});
  for (const bool rule : {true, false}) {
    ObstacleMapOptions o;
    o.forget_in_view_after = 3.0;
    o.laser_clears_stereo = rule;
    ObstacleMap map(o);
    const int64_t t0 = 100 * kS;
    for (int i = 0; i < 3; ++i) {
      map.insert_stereo(seen, {0, 0, 1.25}, robot, 0.0, t0 + i * kS / 10, &view);
      map.insert_laser(present, robot, base_from_laser);
    }
    ASSERT_GE(cell_value(map.project(robot, 1), 0.0, 1.21), 50);
    ASSERT_GE(cell_value(map.project(robot, 1), 0.55, 0.0), 50);
    // 3 s of looking ahead while the laser no longer sees them.
    const auto ahead = seen_by(table_scene(1.5, 2.0), view);
    for (int i = 3; i <= 30; ++i) {
      map.insert_stereo(ahead, {0, 0, 1.25}, robot, 0.0, t0 + i * kS / 10, &view);
      map.insert_laser(gone, robot, base_from_laser);
    }
    const ObstacleGrid g = map.project(robot, 2);
    int person_cells = 0;
    for (double x = -0.15; x <= 0.15; x += 0.05)
      for (double y = 1.1; y <= 1.3; y += 0.05) person_cells += cell_value(g, x, y) >= 50;
    if (rule) {
      EXPECT_EQ(person_cells, 0);
      EXPECT_GT(map.laser_cleared(), 0);
    } else {
      EXPECT_GT(person_cells, 0);
      EXPECT_EQ(map.laser_cleared(), 0);
    }
    EXPECT_GE(cell_value(g, 0.55, 0.0), 50) << rule;   // the seat: the laser saw nothing in its column
    EXPECT_GE(cell_value(g, 1.75, 0.0), 50) << rule;   // the table top ahead
  }
}

TEST(ObstacleMap, FloorPointsAreNotObstacles)
{
  // Noisy floor (within the tolerance): still free.
  ObstacleMap map({});
  std::vector<Eigen::Vector3f> pts;
  cv::RNG rng(5);
  for (double x = 0.6; x < 3.0; x += 0.02)
    for (double y = -1.0; y <= 1.0; y += 0.02) pts.emplace_back(x, y, static_cast<float>(rng.uniform(-0.04, 0.04)));
  map.insert_stereo(pts, {0, 0, 1.25}, Pose2(0, 0, 0));
  const ObstacleGrid g = map.project(Pose2(0, 0, 0), 1);
  int occupied = 0, free = 0;
  for (int8_t c : g.cells) {
    if (c >= 50) ++occupied;
    if (c == 0) ++free;
  }
  EXPECT_EQ(occupied, 0);
  EXPECT_GT(free, 1000);
}

TEST(ObstacleMap, DropOffBecomesAnObstacle)
{
  // The floor ends at x = 2 (stairs down): points beyond it lie 1 m below the floor.
  ObstacleMap map({});
  std::vector<Eigen::Vector3f> pts;
  for (double y = -0.5; y <= 0.5; y += 0.02) {
    for (double x = 0.6; x < 2.0; x += 0.02) pts.emplace_back(x, y, 0.0);
    for (double x = 2.0 * 2.25 / 1.25; x < 4.0; x += 0.02) pts.emplace_back(x, y, -1.0);
  }
  map.insert_stereo(pts, {0, 0, 1.25}, Pose2(0, 0, 0));
  const ObstacleGrid g = map.project(Pose2(0, 0, 0), 1);
  EXPECT_EQ(cell_value(g, 1.0, 0.0), 0);
  // The rays beyond the edge cross the floor plane at x >= 2: obstacles there.
  EXPECT_EQ(cell_value(g, 2.1, 0.0), 100);
  EXPECT_EQ(cell_value(g, 2.1, 0.3), 100);
}

sensors::LaserScan laser_scan(double range_ahead, double range_elsewhere)
{
  sensors::LaserScan s;
  s.angle_min = -M_PI / 2;
  s.angle_increment = M_PI / 180;
  s.range_min = 0.05;
  s.range_max = 30.0;
  for (int i = 0; i <= 180; ++i) s.ranges.push_back(std::abs(s.bearing(i)) < 0.1 ? range_ahead : range_elsewhere);
  return s;
}

TEST(ObstacleMap, LaserIsFusedInItsLayer)
{
  ObstacleMapOptions o;
  o.laser_only_obstacles = true;
  ObstacleMap map(o);
  const Pose2 robot(0, 0, 0);
  // A laser wall at x = 3 ahead: an obstacle in the grid even where stereo saw nothing.
  for (int i = 0; i < 3; ++i) map.insert_laser(laser_scan(3.0, 30.0), robot, Pose2(0.12, 0, 0));
  ObstacleGrid g = map.project(robot, 1);
  EXPECT_GE(cell_value(g, 3.14, 0.0), 50);
  EXPECT_EQ(cell_value(g, 2.0, 0.0), 0);

  // Stereo sees a thin spurious blob at the laser's height at x = 2 (one view); the laser,
  // which sees through it several times, outweighs it: the fused cell is free.
  std::vector<Eigen::Vector3f> blob;
  for (double y = -0.05; y <= 0.05; y += 0.01) blob.emplace_back(2.0, y, 0.42);
  map.insert_stereo(blob, {0, 0, 1.25}, robot);
  g = map.project(robot, 2);
  EXPECT_LT(cell_value(g, 2.0, 0.0), 50);

  // By default laser hits that stereo never saw stay out of the grid (free evidence only).
  ObstacleMapOptions d;
  ObstacleMap quiet(d);
  for (int i = 0; i < 3; ++i) quiet.insert_laser(laser_scan(3.0, 30.0), robot, Pose2(0.12, 0, 0));
  EXPECT_EQ(cell_value(quiet.project(robot, 1), 3.14, 0.0), 0);

  // Without the laser the same blob is an obstacle: the fusion is what clears it.
  ObstacleMap stereo_only(o);
  stereo_only.insert_stereo(blob, {0, 0, 1.25}, robot);
  EXPECT_GE(cell_value(stereo_only.project(robot, 2), 2.0, 0.0), 50);
}

TEST(ObstacleMap, GridIsEgocentricAndOnTheVoxelLattice)
{
  ObstacleMapOptions o;
  o.grid_size = 4.0;
  ObstacleMap map(o);
  const Pose2 robot(10.33, -4.71, 0.8);
  map.insert_stereo(table_scene(1.5, 2.0), {0, 0, 1.25}, robot);
  const ObstacleGrid g = map.project(robot, 5);
  EXPECT_EQ(g.width, 80);
  EXPECT_EQ(g.height, 80);
  EXPECT_EQ(g.cells.size(), 6400u);
  EXPECT_EQ(g.odom_from_grid.theta(), 0.0);
  // The robot is within a cell of the grid's centre.
  EXPECT_NEAR(g.odom_from_grid.x() + 2.0, robot.x(), 0.05 + 1e-9);
  EXPECT_NEAR(g.odom_from_grid.y() + 2.0, robot.y(), 0.05 + 1e-9);
  // The table 1.75 m ahead of the robot (in its heading) is occupied in the odometry frame.
  const Eigen::Vector2d table = robot * Eigen::Vector2d(1.75, 0.0);
  EXPECT_GE(cell_value(g, table.x(), table.y()), 50);
}

TEST(ObstacleMap, MemoryStaysBoundedOnALongDrive)
{
  ObstacleMapOptions o;
  o.keep_radius = 4.0;
  o.reanchor_distance = 25.0;
  ObstacleMap map(o);
  // Along a corridor with walls at y = +-1.2 and a floor, 60 m in 1 m steps.
  std::vector<Eigen::Vector3f> view;
  for (double x = 0.5; x < 4.0; x += 0.2)
    for (double z = 0.0; z < 2.0; z += 0.2) {
      view.emplace_back(x, 1.2, z);
      view.emplace_back(x, -1.2, z);
    }
  for (double x = 0.5; x < 4.0; x += 0.2)
    for (double y = -1.15; y < 1.2; y += 0.2) view.emplace_back(x, y, 0.0);
  size_t leaves_at_10m = 0, most = 0;
  for (int i = 0; i <= 60; ++i) {
    const Pose2 robot(1.0 * i, 0.0, 0.0);
    map.insert_stereo(view, {0, 0, 1.25}, robot);
    if (i == 10) leaves_at_10m = map.leaf_count();
    if (i > 10 && i % 5 == 0) most = std::max(most, map.leaf_count());
  }
  EXPECT_GT(map.trims(), 50);
  // Re-anchored at 26 m and 52 m: the map started afresh around the robot twice.
  EXPECT_EQ(map.reanchors(), 2);
  ASSERT_GT(leaves_at_10m, 0u);
  EXPECT_LT(most, 2 * leaves_at_10m);
  // The walls beside the robot at the end of the drive are still there (a point every 0.2 m).
  const Pose2 end(60.0, 0, 0);
  const ObstacleGrid g = map.project(end, 1);
  int left = 0, right = 0;
  for (double x = 60.52; x < 63.9; x += 0.05) {
    left += cell_value(g, x, 1.22) >= 50;
    right += cell_value(g, x, -1.23) >= 50;
  }
  EXPECT_GE(left, 12);
  EXPECT_GE(right, 12);
}

TEST(ObstacleMap, TrimWithoutItTheMapGrows)
{
  // The rule tested the other way: with a keep radius beyond the drive nothing is deleted and
  // the leaf count grows with the distance driven.
  ObstacleMapOptions o;
  o.keep_radius = 1000.0;
  ObstacleMap map(o);
  std::vector<Eigen::Vector3f> view;
  for (double x = 0.5; x < 4.0; x += 0.2)
    for (double z = 0.0; z < 2.0; z += 0.2) view.emplace_back(x, 1.2, z);
  size_t at_5m = 0;
  for (int i = 0; i <= 60; ++i) {
    map.insert_stereo(view, {0, 0, 1.25}, Pose2(0.5 * i, 0.0, 0.0));
    if (i == 10) at_5m = map.leaf_count();
  }
  EXPECT_GT(map.leaf_count(), 3 * at_5m);
}

TEST(OctreeTrim, RemovesOnlyWhatIsOutside)
{
  octomap::OcTree tree(0.1);
  for (double x = -10; x <= 10; x += 0.1)
    for (double y = -10; y <= 10; y += 0.5) tree.updateNode(octomap::point3d(x, y, 0.5), true);
  const size_t before = tree.getNumLeafNodes();
  EXPECT_GT(trim_tree(tree, {2.0, 0.0}, 3.0), 0u);
  size_t inside = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    EXPECT_LE(std::hypot(it.getX() - 2.0, it.getY()), 3.0 + it.getSize());
    ++inside;
  }
  EXPECT_LT(inside, before / 10);
  EXPECT_GT(inside, 50u);
  // Still a working tree: new updates far away and a second trim.
  tree.updateNode(octomap::point3d(-50, 40, 1), true);
  EXPECT_NE(tree.search(octomap::point3d(-50, 40, 1)), nullptr);
  trim_tree(tree, {-50, 40}, 0.5);
  EXPECT_EQ(tree.search(octomap::point3d(0, 0, 0.5)), nullptr);
  EXPECT_NE(tree.search(octomap::point3d(-50, 40, 1)), nullptr);
  trim_tree(tree, {500, 500}, 0.5);   // nothing left within
  EXPECT_EQ(tree.getNumLeafNodes(), 0u);
}

}  // namespace
}  // namespace rgnav::vision
