// The vision process over a FakeBus with the simulated head's calibration: a textured wall
// 2 m ahead becomes a line of occupied cells in OBSTACLES_3D; frames that name another
// calibration, do not decode or have the wrong size are dropped and counted; odometry that
// restarts starts the map afresh; bad config is refused naming file and key; the process checks
// its shipped config and stops cleanly on SIGTERM.
#include "vision/vision_node.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <csignal>
#include <fstream>
#include <thread>

#include "bad_files.h"
#include "bus/typed.h"
#include "child_process.h"
#include "config/config.h"
#include "config/robot_description.h"
#include "drivers/stereo/image_encoding.h"
#include "drivers/stereo/stereo_calibration.h"
#include "fake_bus_node.h"
#include "msg/conversions.h"
#include "rgnav/objects3d_t.hpp"
#include "rgnav/obstacle_grid_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "synthetic_stereo.h"
#include "vision/rig_from_calibration.h"
#include "vision/vision_conversions.h"
#include "vision/vision_options.h"

namespace rgnav::vision {
namespace {

using geometry::Pose2;

constexpr int64_t kT0 = 1'700'000'000'000'000;
const std::string kConfig = RGNAV_SOURCE_DIR "/config/vision.yaml";

config::RobotDescription robot() { return config::load_robot_description_file(RGNAV_SOURCE_DIR "/config/robot.yaml"); }

VisionNodeOptions shipped_options() { return load_vision_options(config::Config::load(kConfig), robot(), kConfig); }

StereoRig shipped_rig(const VisionNodeOptions& o)
{
  return rig_from_calibration(stereo::load_stereo_calibration(o.calibration_file));
}

struct Fixture
{
  VisionNodeOptions options = shipped_options();
  testing::FakeBusNode fake{"vision"};
  std::unique_ptr<VisionNode> node;
  int64_t odometry_seq = 0;
  int64_t frame_id = 0;

  explicit Fixture(bool laser_only_obstacles = false)
  {
    options.vision.map.laser_only_obstacles = laser_only_obstacles;
    node = std::make_unique<VisionNode>(*fake.node, options, shipped_rig(options));
  }

  void odometry(int64_t utime, const Pose2& pose = Pose2(0, 0, 0))
  {
    odometry_t m{};
    m.utime = utime;
    m.seq = ++odometry_seq;
    m.odom_from_base = msg::to_msg(pose);
    m.status = odometry_t::STATUS_SIMULATED;
    ASSERT_TRUE(bus::publish(*fake.bus, "ODOMETRY", m));
  }

  stereo_images_t frame(int64_t utime, int disparity = 30, stereo::Encoding enc = stereo::Encoding::kRaw)
  {
    const auto pair = synthetic::plane_pair(cv::Size(640, 480), disparity, 17);
    stereo_images_t m;
    m.utime = utime;
    m.frame_id = ++frame_id;
    m.calibration_id = "sim_b21r_head";
    m.pan = 0;
    m.tilt = 0;
    m.left = stereo::encode_image(pair.left, utime, enc, 95);
    m.right = stereo::encode_image(pair.right, utime, enc, 95);
    return m;
  }

  void send(const stereo_images_t& m) { ASSERT_TRUE(bus::publish(*fake.bus, "STEREO_IMAGES", m)); }
  // As another process could send it: LCM's own encoding, none of rgnav's checks.
  void send_unchecked(const stereo_images_t& m)
  {
    std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
    ASSERT_GE(m.encode(bytes.data(), 0, static_cast<int>(bytes.size())), 0);
    ASSERT_TRUE(fake.bus->publish("STEREO_IMAGES", bytes.data(), bytes.size()));
  }
  std::vector<obstacle_grid_t> grids() const { return testing::decoded<obstacle_grid_t>(*fake.bus, "OBSTACLES_3D"); }
};

TEST(VisionNode, AWallAheadBecomesOccupiedCells)
{
  Fixture f;
  f.odometry(kT0);
  f.send(f.frame(kT0 + 50'000, 30, stereo::Encoding::kJpeg));
  EXPECT_TRUE(f.grids().empty()) << "processed before the odometry after its capture";
  f.odometry(kT0 + 100'000);
  const auto grids = f.grids();
  ASSERT_EQ(grids.size(), 1u);
  const ObstacleGrid g = from_msg(grids[0]);
  EXPECT_EQ(g.utime, kT0 + 50'000);
  EXPECT_EQ(g.width, 160);
  EXPECT_NEAR(g.resolution, 0.05, 1e-6);
  // The wall is 2 m (f * B / d) in front of the left camera, whose optical centre is 0.09 m
  // ahead of the base (head 0.05 m + camera 0.04 m on it).
  const double wall_x = 0.09 + 500.0 * 0.12 / 30;
  int on_wall = 0, elsewhere = 0;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      if (g.at(x, y) < 50) continue;
      const double cx = g.odom_from_grid.x() + (x + 0.5) * g.resolution;
      if (std::abs(cx - wall_x) < 0.1) ++on_wall;
      else ++elsewhere;
    }
  EXPECT_GT(on_wall, 20);
  EXPECT_LT(elsewhere, on_wall / 10);
  // Between the robot and the wall the space is seen free.
  int cx, cy;
  ASSERT_TRUE(g.cell_of({1.0, 0.0}, &cx, &cy));
  EXPECT_EQ(g.at(cx, cy), 0);
  EXPECT_EQ(f.node->frames_processed(), 1);
  EXPECT_EQ(f.fake.node->drops().total(), 0);
}

// A whiteboard on the wall (a bright rectangle 150 x 100 px with a dark rim, on the textured
// wall 2 m ahead): OBJECTS_3D carries it in the base frame, upright, facing the robot, its size
// f * B / d from the pixels (0.6 x 0.4 m), on the wall, a whiteboard by the white inside it.
TEST(VisionNode, ARectangleOnTheWallIsPublishedAsAnObject)
{
  Fixture f;
  constexpr int kDisparity = 30;
  auto pair = synthetic::plane_pair(cv::Size(640, 480), kDisparity, 17);
  for (const auto& [img, shift] : {std::make_pair(&pair.left, 0), std::make_pair(&pair.right, kDisparity)}) {
    const cv::Rect board(250 - shift, 190, 150, 100);
    cv::rectangle(*img, board, cv::Scalar(25), cv::FILLED);
    cv::rectangle(*img, cv::Rect(board.x + 4, board.y + 4, board.width - 8, board.height - 8), cv::Scalar(235), cv::FILLED);
  }
  stereo_images_t m = f.frame(kT0 + 50'000);
  m.left = stereo::encode_image(pair.left, m.utime, stereo::Encoding::kRaw, 95);
  m.right = stereo::encode_image(pair.right, m.utime, stereo::Encoding::kRaw, 95);
  f.odometry(kT0);
  f.send(m);
  f.odometry(kT0 + 100'000);
  const auto objects = testing::decoded<objects3d_t>(*f.fake.bus, "OBJECTS_3D");
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_EQ(objects[0].utime, kT0 + 50'000);
  const double wall_x = 0.09 + 500.0 * 0.12 / kDisparity;
  int boards = 0;
  for (const auto& r : objects[0].rectangles) {
    if (std::abs(r.width - 0.6) > 0.06 || std::abs(r.height - 0.4) > 0.06) continue;
    ++boards;
    EXPECT_LT(r.normal[0], -0.95);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(r.corners[i][0], wall_x, 0.08);
    EXPECT_EQ(r.kind, rectangle3d_t::KIND_WHITEBOARD);
  }
  EXPECT_GE(boards, 1) << objects[0].nrectangles << " rectangles, none of the board's size";
}

TEST(VisionNode, BadFramesAreDroppedAndCounted)
{
  Fixture f;
  f.odometry(kT0);
  int64_t t = kT0;
  int64_t drops = 0;
  const auto expect_dropped = [&](stereo_images_t m, const char* what) {
    f.send_unchecked(m);
    f.odometry(t += 100'000);
    EXPECT_EQ(f.fake.node->drops().total(), ++drops) << what;
    EXPECT_TRUE(f.grids().empty()) << what;
  };
  auto m = f.frame(t + 50'000);
  m.calibration_id = "another_rig";
  expect_dropped(m, "another calibration");

  m = f.frame(t + 50'000);
  const cv::Mat small(240, 320, CV_8UC1, cv::Scalar(90));
  m.left = stereo::encode_image(small, m.utime, stereo::Encoding::kRaw, 90);
  m.right = stereo::encode_image(small, m.utime, stereo::Encoding::kRaw, 90);
  expect_dropped(m, "wrong size");

  m = f.frame(t + 50'000, 30, stereo::Encoding::kJpeg);
  m.right.data.resize(40);   // a JPEG header and nothing after it
  m.right.size = 40;
  expect_dropped(m, "does not decode");

  m = f.frame(t + 50'000);
  m.tilt = std::nan("");
  expect_dropped(m, "head angle NaN");

  // A raw image whose size disagrees with its buffer never reaches the node (message checks).
  m = f.frame(t + 50'000);
  m.left.size = 100;
  m.left.data.resize(100);
  expect_dropped(m, "malformed image_t");

  // A good frame after all that is processed.
  f.send(f.frame(t + 50'000));
  f.odometry(t += 100'000);
  EXPECT_EQ(f.grids().size(), 1u);
  EXPECT_EQ(f.fake.node->drops().total(), drops);
}

TEST(VisionNode, OnlyTheNewestFrameWaitsForOdometry)
{
  Fixture f;
  f.odometry(kT0);
  f.send(f.frame(kT0 + 20'000));
  f.send(f.frame(kT0 + 40'000));
  f.send(f.frame(kT0 + 60'000));
  f.odometry(kT0 + 80'000);
  EXPECT_EQ(f.grids().size(), 1u);
  EXPECT_EQ(f.node->frames_superseded(), 2);
  EXPECT_EQ(from_msg(f.grids()[0]).utime, kT0 + 60'000);
}

TEST(VisionNode, OdometryRestartStartsTheMapAfresh)
{
  Fixture f;
  f.odometry(kT0);
  f.send(f.frame(kT0 + 50'000));
  f.odometry(kT0 + 100'000);
  ASSERT_GT(f.node->pipeline().map().leaf_count(), 0u);
  f.odometry_seq = 0;   // the base driver restarted: sequence and frame from the start
  f.odometry(kT0 + 200'000, Pose2(0, 0, 0));
  EXPECT_EQ(f.node->map_resets(), 1);
  EXPECT_EQ(f.node->pipeline().map().leaf_count(), 0u);
}

TEST(VisionNode, LaserScansAreFusedAtTheirPeriod)
{
  Fixture f(true);   // laser hits alone are obstacles of the grid: they can be seen in it
  f.odometry(kT0);
  for (int i = 1; i <= 30; ++i) {
    laser_scan_t s{};
    s.utime = kT0 + i * 13'333;
    s.scan_id = i;
    s.angle_min = -M_PI / 2;
    s.angle_increment = M_PI / 180;
    s.range_min = 0.05f;
    s.range_max = 30.f;
    s.nranges = 181;
    s.ranges.assign(181, 2.0f);
    ASSERT_TRUE(bus::publish(*f.fake.bus, "LASER_FRONT", s));
    f.odometry(kT0 + i * 13'333 + 1'000);
  }
  // 0.4 s of scans at 75 Hz, fused every 0.1 s.
  EXPECT_GE(f.node->laser_scans_fused(), 4);
  EXPECT_LE(f.node->laser_scans_fused(), 5);
  f.send(f.frame(kT0 + 420'000));
  f.odometry(kT0 + 450'000);
  ASSERT_EQ(f.grids().size(), 1u);
  const ObstacleGrid g = from_msg(f.grids()[0]);
  int cx, cy;
  // The laser's half circle of hits at 2 m round its position (0.12 m ahead), also far to the
  // side where the camera does not look.
  ASSERT_TRUE(g.cell_of({0.12 + 2.0 * std::cos(1.4), 2.0 * std::sin(1.4)}, &cx, &cy));
  EXPECT_GE(g.at(cx, cy), 50);
}

TEST(VisionConversions, GridRoundTrip)
{
  ObstacleGrid g;
  g.utime = kT0;
  g.odom_from_grid = Pose2(-3.25, 7.5, 0.0);
  g.resolution = 0.05;
  g.width = 3;
  g.height = 2;
  g.cells = {-1, 0, 100, 70, 49, 50};
  g.min_height = 0.1;
  g.max_height = 1.45;
  std::vector<uint8_t> bytes;
  std::string why;
  const obstacle_grid_t m = to_msg(g);
  ASSERT_TRUE(bus::encode(m, &bytes, &why)) << why;   // the message checks accept it
  obstacle_grid_t back;
  ASSERT_TRUE(bus::decode(bytes.data(), bytes.size(), &back, &why)) << why;
  const ObstacleGrid r = from_msg(back);
  EXPECT_EQ(r.utime, g.utime);
  EXPECT_DOUBLE_EQ(r.odom_from_grid.x(), -3.25);
  EXPECT_DOUBLE_EQ(r.odom_from_grid.y(), 7.5);
  EXPECT_NEAR(r.resolution, 0.05, 1e-7);
  EXPECT_EQ(r.width, 3);
  EXPECT_EQ(r.height, 2);
  EXPECT_EQ(r.cells, g.cells);
  EXPECT_EQ(r.at(2, 0), 100);
  EXPECT_EQ(r.at(0, 1), 70);
  EXPECT_NEAR(r.max_height, 1.45, 1e-6);
}

TEST(VisionCalibration, RigFollowsTheCalibrationsHeadKinematics)
{
  const auto cal = stereo::load_stereo_calibration(RGNAV_SOURCE_DIR "/config/stereo/sim_b21r_head.yml");
  const StereoRig rig = rig_from_calibration(cal);
  EXPECT_TRUE(check_rig(rig).empty()) << check_rig(rig);
  for (const double pan : {0.0, 0.7, -2.0})
    for (const double tilt : {0.0, -0.4, 0.3}) {
      const Eigen::Isometry3d a = base_from_camera(rig, pan, tilt);
      const Eigen::Isometry3d b = stereo::base_from_left_camera(cal, pan, tilt);
      EXPECT_TRUE(a.matrix().isApprox(b.matrix(), 1e-12)) << "pan " << pan << " tilt " << tilt;
    }
}

TEST(VisionOptions, BadConfigIsRefusedNamingFileAndKey)
{
  const auto refused = [](const std::string& yaml, const std::string& key) {
    SCOPED_TRACE(key);
    const auto cfg = config::Config::parse(yaml, "test/vision.yaml");
    try {
      load_vision_options(cfg, robot(), kConfig);
      cfg.finish();
      ADD_FAILURE() << "accepted";
    } catch (const config::ConfigError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("test/vision.yaml"), std::string::npos) << what;
      EXPECT_NE(what.find(key), std::string::npos) << what;
    }
  };
  refused("disparity:\n  num_disparities: 50\n", "disparity.num_disparities");
  refused("disparity:\n  block_size: 4\n", "disparity.block_size");
  refused("disparity:\n  mode: fast\n", "disparity.mode");
  refused("disparity:\n  downscale: 3\n", "disparity.downscale");
  refused("map:\n  resolution_m: 0\n", "map.resolution_m");
  refused("map:\n  keep_radius_m: 4\n  grid_size_m: 9\n", "map.grid_size_m");
  refused("vision:\n  calibration_id: ../etc/passwd\n", "vision.calibration_id");
  refused("map:\n  max_rnage_m: 4\n", "map.max_rnage_m");
  // The shipped file passes.
  const auto cfg = config::Config::load(kConfig);
  EXPECT_NO_THROW({
    runtime::load_node_options(cfg.section("node"), "vision");
    load_vision_options(cfg, robot(), kConfig);
    cfg.finish();
  });
}

TEST(VisionProcess, RefusesABadCalibrationChecksItsConfigAndStopsCleanly)
{
  testing::TempDir dir("vision_process");
  testing::ChildOptions o;
  o.stderr_path = dir.file("stderr");
  auto status = testing::run_to_completion({RGNAV_VISION_BIN, "--config", kConfig, "--check-config"}, std::chrono::seconds(30), o);
  EXPECT_TRUE(status.clean()) << status.describe() << testing::read_file(dir.file("stderr"));

  // A calibration file of random bytes, empty or cut off: refused naming it.
  const std::string good = testing::read_file(RGNAV_SOURCE_DIR "/config/stereo/sim_b21r_head.yml");
  for (const auto& bad : testing::write_bad_files(dir.path(), "rig.yml", good)) {
    SCOPED_TRACE(bad.kind);
    {
      std::ofstream(dir.file("vision.yaml")) << "vision:\n  calibration_file: " << bad.path << "\n";
      std::ofstream(dir.file("robot.yaml")) << testing::read_file(RGNAV_SOURCE_DIR "/config/robot.yaml");
    }
    status = testing::run_to_completion({RGNAV_VISION_BIN, "--config", dir.file("vision.yaml"), "--check-config"},
                                        std::chrono::seconds(30), o);
    EXPECT_TRUE(status.exited && status.code == 2) << status.describe();
    const std::string err = testing::read_file(dir.file("stderr"));
    EXPECT_NE(err.find(bad.path), std::string::npos) << err;
  }

  // Running on an in-process bus: SIGTERM ends it with 0. Sent once its node runs (it says so): a
  // signal that comes while the calibration is still loading, before the node watches for it,
  // ends the process as the default action does — a loaded machine took longer than a fixed wait.
  testing::ChildProcess child({RGNAV_VISION_BIN, "--config", kConfig, "--lcm-url", "memq://"}, o);
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (child.running() && child.stderr_text().find("running on") == std::string::npos &&
         std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(child.running()) << child.stderr_text();
  ASSERT_NE(child.stderr_text().find("running on"), std::string::npos) << child.stderr_text();
  testing::expect_clean_stop(child);
}

}  // namespace
}  // namespace rgnav::vision
