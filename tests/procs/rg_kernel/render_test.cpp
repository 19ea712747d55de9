#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>

#include "bad_files.h"
#include "persist/checked_json.h"
#include "rgmap/saved_map.h"
#include "procs/rg_kernel/rg_kernel.h"
#include "render/rgmap_picture.h"
#include "rgmap/rgmap_json.h"
#include "synthetic_world.h"

namespace rgnav::rg_kernel {
namespace {

using Eigen::Vector2d;

rgmap::RgMap two_room_map()
{
  RgKernel k{KernelOptions{}};
  const auto walls = testing::two_rooms();
  int64_t id = 1, t = 0;
  auto scan = [&](double x, double th) {
    ScanInput s;
    s.scan_id = id++;
    s.utime = (t += 200'000);
    s.map_from_base = geometry::Pose2(x, 1.5, th);
    s.laser_points = testing::cast(walls, s.map_from_base);
    k.add_scan(s);
  };
  for (double x = 0.8; x < 3.8; x += 0.2) scan(x, 0.3 * std::sin(x * 3));
  GatewayEventInput e;
  e.utime = (t += 1000);
  e.cls = rgmap::GatewayClass::kDoor;
  e.map_from_base = geometry::Pose2(4.3, 1.5, 0);
  e.gateway_points = {Vector2d(4, 1), Vector2d(4, 2)};
  e.track_id = 1;
  k.add_gateway_event(e);
  for (double x = 4.5; x < 7.5; x += 0.2) scan(x, 0.3 * std::sin(x * 3) + (x > 6 ? M_PI : 0));
  e.utime = (t += 1000);
  e.map_from_base = geometry::Pose2(3.7, 1.5, M_PI);
  k.add_gateway_event(e);  // back into room A: room B gets finalised too
  return k.refreshed_map();
}

TEST(Render, PicturesAndMapServerExport)
{
  const auto dir = std::filesystem::path(::testing::TempDir()) / ("render_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const rgmap::RgMap map = two_room_map();
  ASSERT_EQ(map.regions().size(), 2u);

  render::render_rgmap(map, (dir / "map.svg").string());
  render::render_rgmap(map, (dir / "map.png").string());
  std::ifstream svg(dir / "map.svg");
  const std::string svg_text((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
  EXPECT_NE(svg_text.find("<svg"), std::string::npos);
  EXPECT_NE(svg_text.find(">door<"), std::string::npos);  // the gateway is labelled with its class
  EXPECT_NE(svg_text.find(">R1"), std::string::npos);
  const cv::Mat png = cv::imread((dir / "map.png").string());
  ASSERT_FALSE(png.empty());
  EXPECT_GT(png.cols, 8 * 40);  // 8 m wide at 40 px/m, plus margins

  const auto grid = render::compose_global_grid(map, 0.05);
  render::write_map_server(grid, (dir / "global").string());
  const cv::Mat pgm = cv::imread((dir / "global.pgm").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(pgm.empty());
  auto at = [&](double x, double y) {
    const int cx = static_cast<int>((x - grid.origin.x()) / grid.resolution);
    const int cy = pgm.rows - 1 - static_cast<int>((y - grid.origin.y()) / grid.resolution);
    return pgm.at<uint8_t>(cy, cx);
  };
  EXPECT_EQ(at(2.0, 1.5), 254);   // inside room A
  EXPECT_EQ(at(6.0, 1.5), 254);   // inside room B (its own region's freespace)
  EXPECT_EQ(at(2.0, 0.0), 0);     // the wall y = 0
  EXPECT_EQ(at(2.0, -0.4), 205);  // outside: unknown
  std::ifstream yaml(dir / "global.yaml");
  const std::string y((std::istreambuf_iterator<char>(yaml)), std::istreambuf_iterator<char>());
  EXPECT_NE(y.find("image: global.pgm"), std::string::npos);
  EXPECT_NE(y.find("resolution: 0.05"), std::string::npos);
}

// Issue 35: ./rgnav render on random bytes, an empty file, a cut-off rgmap.json, and a whole
// checked file that is no RG map: exit non-zero, the file named, no picture or export written.
TEST(Render, BadFilesAreRefusedNamingThemAndNothingIsWritten)
{
  rgnav::testing::TempDir dir("render_bad");
  const std::string valid = dir.file("rgmap.json");
  rgmap::save_map(two_room_map(), valid);
  auto files = rgnav::testing::write_bad_files(dir.path(), "rgmap.json", rgnav::testing::read_file(valid));
  files.push_back({"not an RG map", dir.file("other.json")});
  persist::write_json_atomically(files.back().path, {{"schema", "something else"}});
  for (const auto& f : files) {
    SCOPED_TRACE(f.kind);
    const std::string out = dir.file("out.png"), base = dir.file("export");
    const auto r = rgnav::testing::run_tool({RGNAV_RENDER_BIN, f.path, "--out", out, "--export-pgm", base}, dir.path());
    EXPECT_TRUE(r.status.exited && r.status.code != 0) << r.status.describe();
    EXPECT_NE(r.err.find(f.path), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_FALSE(std::filesystem::exists(base + ".pgm"));
    EXPECT_FALSE(std::filesystem::exists(base + ".yaml"));
  }
  const auto ok = rgnav::testing::run_tool({RGNAV_RENDER_BIN, valid, "--out", dir.file("ok.png")}, dir.path());
  EXPECT_TRUE(ok.status.clean()) << ok.err;   // the same command on the whole file works
}

TEST(Render, RegionFramesComposedThroughGateways)
{
  rgmap::RgMap map = two_room_map();
  // Move region 2's stored map pose away: composition must follow the gateway transform instead.
  map.region(2)->map_from_region = geometry::Pose2(100, 100, 1);
  const auto frames = render::compose_region_frames(map);
  const auto expected = map.region(1)->map_from_region * map.gateway(1)->region_a_from_region_b;
  EXPECT_NEAR(frames.at(2).x(), expected.x(), 1e-9);
  EXPECT_NEAR(frames.at(2).theta(), expected.theta(), 1e-9);
}

}  // namespace
}  // namespace rgnav::rg_kernel
