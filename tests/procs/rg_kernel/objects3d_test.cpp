// The vision's 3D rectangles in the RG map (procs/rg_kernel/objects3d.h, diss. 3.3.5): one object
// seen again is one object, averaged, more confident; others are new; OBJECTS_3D re-anchored by
// the scan id's correction lands in the current region, survives a restart from the journal, and
// a malformed message is dropped and counted.
#include "procs/rg_kernel/objects3d.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "fake_bus_node.h"
#include "kernel_messages.h"
#include "procs/rg_kernel/rg_kernel_node.h"
#include "rgmap/rgmap_json.h"

namespace rgnav::rg_kernel {
namespace {

// A door-sized rectangle, upright, in the plane x = `x`, from y0 to y0 + 1 (frame of the caller).
rgmap::Rectangle3d door(double x, double y0, int8_t kind = 1)
{
  rgmap::Rectangle3d r;
  r.corners << x, y0, 0.0, x, y0 + 1.0, 0.0, x, y0 + 1.0, 2.1, x, y0, 2.1;
  r.normal = Eigen::Vector3d(-1, 0, 0);
  r.width = 1.0;
  r.height = 2.1;
  r.kind = kind;
  return r;
}

TEST(Objects3d, TheSameObjectSeenAgainIsAveragedOthersAreNew)
{
  std::vector<rgmap::Rectangle3d> objects;
  int64_t next = 500;
  Objects3dOptions o;
  merge_objects3d(&objects, {door(4.0, 1.0)}, &next, o);
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_EQ(objects[0].id, 500);
  // Seen again 10 cm off, its corners listed from another corner: one object, halfway.
  rgmap::Rectangle3d again = door(4.1, 1.0);
  again.corners.row(0).swap(again.corners.row(2));
  again.corners.row(1).swap(again.corners.row(3));
  merge_objects3d(&objects, {again}, &next, o);
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_NEAR(objects[0].corners(0, 0), 4.05, 1e-9);
  EXPECT_NEAR(objects[0].corners(0, 1), 1.0, 1e-9);
  EXPECT_NEAR(objects[0].corners(0, 2), 0.0, 1e-9);
  EXPECT_GT(objects[0].confidence, 0.5);
  // Far away, turned, or of another kind: new objects.
  merge_objects3d(&objects, {door(8.0, 1.0), door(4.0, 1.0, 2)}, &next, o);
  rgmap::Rectangle3d turned = door(4.0, 1.0);
  turned.normal = Eigen::Vector3d(0, 1, 0);
  merge_objects3d(&objects, {turned}, &next, o);
  EXPECT_EQ(objects.size(), 4u);
  EXPECT_EQ(objects.back().id, 503);
}

TEST(Objects3d, ToTheRegionFrame)
{
  const auto in_region = to_region_frame({door(4.0, 1.0)}, geometry::Pose2(1.0, 2.0, M_PI / 2));
  // map (4, 1) in a region whose origin is at map (1, 2) turned by 90 degrees: region (-1, -3).
  EXPECT_NEAR(in_region[0].corners(0, 0), -1.0, 1e-9);
  EXPECT_NEAR(in_region[0].corners(0, 1), -3.0, 1e-9);
  EXPECT_NEAR(in_region[0].corners(2, 2), 2.1, 1e-9);
  EXPECT_NEAR(in_region[0].normal.y(), 1.0, 1e-9);
}

objects3d_t door_msg(int64_t utime, int64_t scan_id, double base_x)
{
  // The door at map x = 4 seen from a robot at (base_x, 1.5): in the base frame, x = 4 - base_x.
  objects3d_t m{};
  m.utime = utime;
  m.frame_id = utime;
  m.scan_id = scan_id;
  m.odom_from_base = pose2d_t{base_x, 1.5, 0.0};
  m.nrectangles = 1;
  m.rectangles.resize(1);
  const auto d = door(4.0 - base_x, -0.5);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) m.rectangles[0].corners[i][j] = d.corners(i, j);
  m.rectangles[0].normal[0] = -1.0;
  m.rectangles[0].width = 1.0;
  m.rectangles[0].height = 2.1;
  m.rectangles[0].kind = rectangle3d_t::KIND_DOOR;
  return m;
}

TEST(Objects3d, TheNodeStoresThemInTheCurrentRegionAcrossARestartAndDropsMalformedOnes)
{
  const auto dir = (std::filesystem::path(::testing::TempDir()) / ("rgk_objects3d_" + std::to_string(::getpid()))).string();
  std::filesystem::remove_all(dir);
  NodeConfig c;
  c.state_dir = dir;
  const auto walls = testing::two_rooms();
  std::string before;
  {
    rgnav::testing::FakeBusNode n("rg_kernel");
    RgKernelNode kernel(*n.node, c);
    // Objects before any scan: nowhere to put them.
    ASSERT_TRUE(bus::publish(*n.bus, "OBJECTS_3D", door_msg(900'000, 1, 1.0)));
    EXPECT_EQ(n.node->drops().total(), 1);
    int64_t t = 1'000'000, id = 1;
    for (double x = 1.0; x < 3.0; x += 0.3, t += 200'000)
      ASSERT_TRUE(bus::publish(*n.bus, "ALIGNED_SCAN", testing::aligned_scan_msg(walls, t, id++, pose2d_t{x, 1.5, 0.0})));
    ASSERT_TRUE(bus::publish(*n.bus, "OBJECTS_3D", door_msg(t, id - 1, 2.8)));
    ASSERT_TRUE(bus::publish(*n.bus, "OBJECTS_3D", door_msg(t + 100'000, id - 1, 2.8)));
    objects3d_t bad = door_msg(t + 200'000, id - 1, 2.8);
    bad.rectangles[0].corners[0][0] = std::nan("");
    std::vector<uint8_t> raw(static_cast<size_t>(bad.getEncodedSize()));
    bad.encode(raw.data(), 0, static_cast<int>(raw.size()));  // unchecked: a broken sender
    n.bus->publish("OBJECTS_3D", raw.data(), raw.size());
    objects3d_t huge = door_msg(t + 300'000, id - 1, 2.8);
    huge.rectangles[0].width = 50.0;  // no door, no whiteboard
    ASSERT_TRUE(bus::publish(*n.bus, "OBJECTS_3D", huge));
    EXPECT_EQ(n.node->drops().total(), 3);
    const auto& map = kernel.kernel().map();
    const auto* region = map.region(map.current_region);
    ASSERT_EQ(region->objects3d.size(), 1u);
    const auto back = rgmap::moved(region->objects3d[0], region->map_from_region);
    EXPECT_NEAR(back.corners(0, 0), 4.0, 1e-6);
    EXPECT_NEAR(back.corners(0, 1), 1.0, 1e-6);
    before = rgmap::to_json(map).dump();
  }
  rgnav::testing::FakeBusNode n("rg_kernel");
  RgKernelNode again(*n.node, c);
  EXPECT_EQ(rgmap::to_json(again.kernel().map()).dump(), before);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rgnav::rg_kernel
