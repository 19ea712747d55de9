// 2D objects by line grouping (diss. 3.1-3.2) and circles from scan arcs: synthetic line maps
// and freespace with known furniture, and one end-to-end drive through the kernel.
#include "procs/rg_kernel/object_grouping.h"

#include <gtest/gtest.h>

#include <cmath>

#include <filesystem>
#include <fstream>

#include "procs/rg_kernel/rg_kernel.h"
#include "render/rgmap_picture.h"
#include "rgmap/rgmap_conversions.h"
#include "rgmap/rgmap_json.h"
#include "synthetic_world.h"

namespace rgnav::rg_kernel {
namespace {

using Eigen::Vector2d;
using rgmap::LineSegment;
using rgmap::Object2d;

LineSegment seg(Vector2d a, Vector2d b) { return {a, b, 0.005, 50}; }

// A rotated box: centre, length (along its x), width, heading.
struct Box
{
  Vector2d c;
  double l, w, th;
  Vector2d corner(int k) const   // counter-clockwise from (-l/2, -w/2)
  {
    const double sx[4] = {-0.5, 0.5, 0.5, -0.5}, sy[4] = {-0.5, -0.5, 0.5, 0.5};
    return geometry::Pose2(c, th) * Vector2d(sx[k] * l, sy[k] * w);
  }
  bool inside(const Vector2d& p, double grow) const
  {
    const Vector2d q = geometry::Pose2(c, th).inverse() * p;
    return std::fabs(q.x()) < l / 2 + grow && std::fabs(q.y()) < w / 2 + grow;
  }
};

// The freespace a robot driving around a room [0,W]x[0,H] would carve: the room minus the
// furniture (cells touching a wall or a box stay occupied).
rgmap::FreespaceBitmap room_freespace(double W, double H, const std::vector<Box>& boxes, const std::vector<testing::Pillar>& pillars = {},
                                      double extra_x0 = 0, double extra_y0 = 0, double extra_x1 = 0, double extra_y1 = 0)
{
  const double res = 0.1;
  const int w = static_cast<int>(std::ceil(W / res)) + 20, h = static_cast<int>(std::ceil(H / res)) + 20;
  rgmap::FreespaceBitmap fs(res, geometry::Pose2(-1.0, -1.0, 0.0), w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Vector2d p(-1.0 + (x + 0.5) * res, -1.0 + (y + 0.5) * res);
      const bool in_room = (p.x() > res / 2 && p.x() < W - res / 2 && p.y() > res / 2 && p.y() < H - res / 2) ||
                           (p.x() > extra_x0 && p.x() < extra_x1 && p.y() > extra_y0 && p.y() < extra_y1);
      bool blocked = false;
      for (const auto& b : boxes) blocked |= b.inside(p, res / 2);
      for (const auto& c : pillars) blocked |= (p - c.c).norm() < c.r + res / 2;
      fs.set_free(x, y, in_room && !blocked);
    }
  return fs;
}

std::vector<LineSegment> room_walls(double W, double H)
{
  return {seg({0, 0}, {W, 0}), seg({W, 0}, {W, H}), seg({W, H}, {0, H}), seg({0, H}, {0, 0})};
}

void expect_box(const Object2d& o, const Box& b, double tol)
{
  EXPECT_EQ(o.shape, Object2d::Shape::kRectangle);
  EXPECT_NEAR(o.center.x(), b.c.x(), tol);
  EXPECT_NEAR(o.center.y(), b.c.y(), tol);
  EXPECT_NEAR(o.length, std::max(b.l, b.w), tol);
  EXPECT_NEAR(o.width, std::min(b.l, b.w), tol);
  const double th = b.l >= b.w ? b.th : b.th + M_PI / 2;
  double d = std::remainder(o.center.theta() - th, M_PI);
  EXPECT_LT(std::fabs(d), 2.0 * M_PI / 180) << "heading " << o.center.theta() << " vs " << th;
}

TEST(ObjectGrouping, TableInTheRoomIsOneRectangleAndTheWallsAreNone)
{
  const Box table{{3.0, 2.0}, 1.2, 0.8, 20.0 * M_PI / 180};
  auto segs = room_walls(6, 4);
  for (int k = 0; k < 4; ++k) segs.push_back(seg(table.corner(k), table.corner((k + 1) % 4)));
  const auto objs = group_rectangles(segs, room_freespace(6, 4, {table}), ObjectOptions{});
  ASSERT_EQ(objs.size(), 1u);
  expect_box(objs[0], table, 0.02);
  EXPECT_GT(objs[0].confidence, 0.9);
}

TEST(ObjectGrouping, EmptyRoomAndAlcoveGiveNoObjects)
{
  // A room whose top wall has an alcove 1.0 wide and 0.6 deep: a U of three short walls.
  std::vector<LineSegment> segs = {seg({0, 0}, {6, 0}), seg({6, 0}, {6, 4}), seg({6, 4}, {3.5, 4}), seg({3.5, 4}, {3.5, 4.6}),
                                   seg({3.5, 4.6}, {2.5, 4.6}), seg({2.5, 4.6}, {2.5, 4}), seg({2.5, 4}, {0, 4}), seg({0, 4}, {0, 0})};
  const auto fs = room_freespace(6, 4, {}, {}, 2.55, 3.9, 3.45, 4.55);
  EXPECT_TRUE(group_rectangles(segs, fs, ObjectOptions{}).empty());
  // It is the freespace test that keeps the alcove out: the lines alone group into it.
  ObjectOptions lines_only;
  lines_only.max_inside_free = 1.0;
  lines_only.min_outside_free = 0.0;
  const auto alcove = group_rectangles(segs, fs, lines_only);
  ASSERT_EQ(alcove.size(), 1u);
  EXPECT_NEAR(alcove[0].center.x(), 3.0, 1e-6);
  EXPECT_NEAR(alcove[0].center.y(), 4.3, 1e-6);
  // Without a freespace nothing can be told apart: no guesses.
  EXPECT_TRUE(group_rectangles(segs, rgmap::FreespaceBitmap{}, ObjectOptions{}).empty());
}

TEST(ObjectGrouping, CabinetAgainstTheWallIsCompletedFromThreeSides)
{
  // Cabinet [2,3]x[3.5,4] against the top wall: the wall is seen left and right of it only.
  const Box cabinet{{2.5, 3.75}, 1.0, 0.5, 0.0};
  std::vector<LineSegment> segs = {seg({0, 0}, {6, 0}),     seg({6, 0}, {6, 4}),     seg({6, 4}, {3, 4}), seg({2, 4}, {0, 4}),
                                   seg({0, 4}, {0, 0}),     seg({2, 4}, {2, 3.5}),   seg({2, 3.5}, {3, 3.5}),
                                   seg({3, 3.5}, {3, 4})};
  const auto objs = group_rectangles(segs, room_freespace(6, 4, {cabinet}), ObjectOptions{});
  ASSERT_EQ(objs.size(), 1u);
  expect_box(objs[0], cabinet, 0.02);
}

TEST(ObjectGrouping, BoxWithOneHiddenSide)
{
  // Seen from below, left and right only; the top side is completed at the far ends.
  const Box box{{4.0, 2.5}, 0.8, 0.6, 0.0};
  auto segs = room_walls(6, 4);
  segs.push_back(seg(box.corner(0), box.corner(1)));
  segs.push_back(seg(box.corner(1), box.corner(2) - Vector2d(0, 0.01)));
  segs.push_back(seg(box.corner(3) - Vector2d(0, 0.01), box.corner(0)));
  const auto objs = group_rectangles(segs, room_freespace(6, 4, {box}), ObjectOptions{});
  ASSERT_EQ(objs.size(), 1u);
  expect_box(objs[0], box, 0.03);
  // Fewer observed sides, less confidence than a box seen all round.
  EXPECT_LT(objs[0].confidence, 0.8);

  ObjectOptions no_completion;
  no_completion.complete_three_sides = no_completion.complete_two_sides = false;
  EXPECT_TRUE(group_rectangles(segs, room_freespace(6, 4, {box}), no_completion).empty());
}

TEST(ObjectGrouping, BoxInTheCornerFromTwoSidesAndTooSmallBoxesAreIgnored)
{
  // A box [0,0.8]x[0,0.5] in the room's corner: two sides visible, two against the walls.
  const Box box{{0.4, 0.25}, 0.8, 0.5, 0.0};
  std::vector<LineSegment> segs = {seg({0.8, 0}, {6, 0}), seg({6, 0}, {6, 4}), seg({6, 4}, {0, 4}), seg({0, 4}, {0, 0.5}),
                                   seg({0, 0.5}, {0.8, 0.5}), seg({0.8, 0.5}, {0.8, 0})};
  const auto objs = group_rectangles(segs, room_freespace(6, 4, {box}), ObjectOptions{});
  ASSERT_EQ(objs.size(), 1u);
  expect_box(objs[0], box, 0.02);

  // Smaller than DO_min (0.2 m) across: not an object.
  const Box tiny{{3.0, 2.0}, 0.5, 0.15, 0.0};
  auto segs2 = room_walls(6, 4);
  for (int k = 0; k < 4; ++k) segs2.push_back(seg(tiny.corner(k), tiny.corner((k + 1) % 4)));
  EXPECT_TRUE(group_rectangles(segs2, room_freespace(6, 4, {tiny}), ObjectOptions{}).empty());
}

TEST(ObjectGrouping, CornerGapAndSegmentDistance)
{
  EXPECT_DOUBLE_EQ(corner_gap(seg({0, 0}, {1, 0}), seg({1, 0}, {1, 1})), 0.0);
  EXPECT_NEAR(corner_gap(seg({0, 0}, {1, 0}), seg({1.1, 0.15}, {1.1, 1})), 0.15, 1e-12);
  EXPECT_TRUE(std::isinf(corner_gap(seg({0, 0}, {1, 0}), seg({0, 1}, {1, 1}))));
  EXPECT_NEAR(segment_distance(seg({0, 0}, {1, 0}), seg({0, 1}, {1, 1})), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(segment_distance(seg({0, 0}, {1, 1}), seg({0, 1}, {1, 0})), 0.0);
}

TEST(ObjectGrouping, PillarIsACircleFromScanArcs)
{
  const std::vector<testing::Pillar> pillars = {{{3.0, 2.2}, 0.15}};
  const auto walls = testing::two_rooms();   // room A [0,4]x[0,3] and room B
  std::vector<CircleObservation> obs;
  for (double x = 0.8; x < 2.6; x += 0.2) {
    const geometry::Pose2 pose(x, 1.0, 0.3);
    ScanPoints sp;
    sp.origin = pose.translation();
    for (const auto& p : testing::cast(walls, pose, 8.0, pillars)) sp.points.push_back(pose * p);
    const auto found = circles_in_scan(sp, ObjectOptions{});
    obs.insert(obs.end(), found.begin(), found.end());
  }
  ASSERT_GE(obs.size(), 3u);
  const auto circles = cluster_circles(obs, room_freespace(4, 3, {}, pillars), ObjectOptions{});
  ASSERT_EQ(circles.size(), 1u);
  EXPECT_EQ(circles[0].shape, Object2d::Shape::kCircle);
  EXPECT_NEAR(circles[0].center.x(), 3.0, 0.02);
  EXPECT_NEAR(circles[0].center.y(), 2.2, 0.02);
  EXPECT_NEAR(circles[0].length, 0.30, 0.03);
  // Walls and room corners seen in the same scans give no circle.
  for (const auto& o : obs) EXPECT_LT((o.center - Vector2d(3.0, 2.2)).norm(), 0.05);
}

void check_room_a_objects(const rgmap::Region& r)
{
  const geometry::Pose2 map_from_region = r.map_from_region;
  int rects = 0, circles = 0;
  for (const auto& o : r.objects) {
    const Vector2d c = map_from_region * o.center.translation();
    EXPECT_EQ(o.id / 1000, 1);
    if (o.shape == Object2d::Shape::kRectangle) {
      ++rects;
      EXPECT_NEAR(c.x(), 2.0, 0.05);
      EXPECT_NEAR(c.y(), 2.3, 0.05);
      EXPECT_NEAR(o.length, 0.8, 0.05);
      EXPECT_NEAR(o.width, 0.4, 0.05);
    } else {
      ++circles;
      EXPECT_NEAR(c.x(), 3.2, 0.03);
      EXPECT_NEAR(c.y(), 0.7, 0.03);
      EXPECT_NEAR(o.length, 0.24, 0.03);
    }
  }
  EXPECT_EQ(rects, 1);
  EXPECT_EQ(circles, 1);
}

TEST(ObjectGrouping, KernelFillsObjectsOfTheRegion)
{
  // Room A with a box on the floor and a pillar; the robot drives in and turns back.
  auto walls = testing::two_rooms();
  const auto b = testing::box(1.6, 2.1, 2.4, 2.5);
  walls.insert(walls.end(), b.begin(), b.end());
  const std::vector<testing::Pillar> pillars = {{{3.2, 0.7}, 0.12}};
  RgKernel kernel{KernelOptions{}};
  int64_t id = 1, t = 1'000'000;
  auto scan_at = [&](const geometry::Pose2& pose) {
    ScanInput s;
    s.scan_id = id++;
    s.utime = (t += 200'000);
    s.map_from_base = pose;
    s.laser_points = testing::cast(walls, pose, 8.0, pillars);
    kernel.add_scan(s);
  };
  for (double x = 0.6; x < 3.0; x += 0.2) scan_at(geometry::Pose2(x, 1.5, 0));
  for (double th = 0; th < M_PI; th += 0.3) scan_at(geometry::Pose2(3.0, 1.5, th));
  for (double x = 3.0; x > 0.6; x -= 0.2) scan_at(geometry::Pose2(x, 1.6, M_PI));
  // The open region, as published.
  check_room_a_objects(*kernel.refreshed_map().region(1));
  // Through the door: region 1 is finalised with its objects.
  GatewayEventInput e;
  e.utime = (t += 1000);
  e.kind = GatewayEventInput::Kind::kTraversed;
  e.cls = rgmap::GatewayClass::kDoor;
  e.map_from_base = geometry::Pose2(4.3, 1.5, 0);
  e.gateway_points = {Vector2d(4, 1), Vector2d(4, 2)};
  ASSERT_TRUE(kernel.add_gateway_event(e));
  const rgmap::RgMap& m = kernel.map();
  ASSERT_EQ(m.region(1)->state, rgmap::Region::State::kFinalised);
  check_room_a_objects(*m.region(1));

  // Objects survive the JSON file format and the LCM messages, and are drawn.
  const rgmap::RgMap from_json = rgmap::from_json(nlohmann::json::parse(rgmap::to_json(m).dump()));
  EXPECT_EQ(rgmap::to_json(from_json).dump(), rgmap::to_json(m).dump());
  ASSERT_EQ(from_json.region(1)->objects.size(), m.region(1)->objects.size());
  const rgmap::RgMap from_lcm = rgmap::from_msg(rgmap::to_msg(m));
  ASSERT_EQ(from_lcm.region(1)->objects.size(), m.region(1)->objects.size());
  for (size_t k = 0; k < m.region(1)->objects.size(); ++k) {
    EXPECT_EQ(from_lcm.region(1)->objects[k].shape, m.region(1)->objects[k].shape);
    EXPECT_NEAR(from_lcm.region(1)->objects[k].length, m.region(1)->objects[k].length, 1e-9);
  }
  const auto svg = std::filesystem::path(::testing::TempDir()) / ("objects_" + std::to_string(::getpid()) + ".svg");
  render::render_rgmap(m, svg.string());
  std::ifstream in(svg);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("rgb(120,80,40)"), std::string::npos);   // the box
  EXPECT_NE(text.find("rgb(40,80,120)"), std::string::npos);   // the pillar
}

}  // namespace
}  // namespace rgnav::rg_kernel
