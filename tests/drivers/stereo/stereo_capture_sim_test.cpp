// stereo_capture with the simulated head (source: sim): the shipped config, its checks, and
// pairs published on the fake bus as SIM_TRUTH arrives.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <thread>
#include <limits>

#include "bad_files.h"
#include "child_process.h"
#include "config/config.h"
#include "drivers/stereo/image_encoding.h"
#include "drivers/stereo/stereo_capture_node.h"
#include "fake_bus_node.h"
#include "rgnav/odometry_t.hpp"
#include "rgnav/stereo_images_t.hpp"
#include "sim/sim_stereo_feed.h"
#include "sim/world_yaml.h"

namespace rgnav::stereo {
namespace {

const std::string kConfigDir = std::string(RGNAV_SOURCE_DIR) + "/config";

CaptureOptions shipped_sim_options()
{
  const auto cfg = config::Config::load(kConfigDir + "/stereo_capture_sim.yaml");
  runtime::load_node_options(cfg.section("node"), "stereo_capture");
  auto o = load_capture_options(cfg.section("capture"), cfg.section("channels"), RGNAV_DATA_DIR, kConfigDir);
  cfg.finish();
  return o;
}

odometry_t truth(int64_t utime, double x, double y, double theta)
{
  odometry_t m;
  m.utime = utime;
  m.odom_from_base.x = x;
  m.odom_from_base.y = y;
  m.odom_from_base.theta = theta;
  m.status = odometry_t::STATUS_SIMULATED;
  return m;
}

TEST(StereoCaptureSim, ShippedConfigValidates)
{
  const CaptureOptions o = shipped_sim_options();
  EXPECT_EQ(o.source, CaptureOptions::Source::kSim);
  EXPECT_EQ(o.calibration_id, "sim_b21r_head");
  EXPECT_EQ(o.sim.calibration_file, kConfigDir + "/stereo/sim_b21r_head.yml");
  EXPECT_EQ(o.sim.world_file, kConfigDir + "/worlds/office.yaml");
  EXPECT_EQ(o.sim.truth_channel, "SIM_TRUTH");
  // The real robot's config names the sim keys too (defaults) and still validates.
  const auto real = config::Config::load(kConfigDir + "/stereo_capture.yaml");
  runtime::load_node_options(real.section("node"), "stereo_capture");
  load_capture_options(real.section("capture"), real.section("channels"), RGNAV_DATA_DIR, kConfigDir);
  EXPECT_NO_THROW(real.finish());
}

TEST(StereoCaptureSim, MissingCalibrationOrWorldRefusedNamingTheKey)
{
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"capture: {source: sim, calibration_id: no_such_rig}\n", "capture.calibration_id"},
      {"capture: {source: sim, calibration_id: ../sim}\n", "capture.calibration_id"},
      {"capture: {source: sim, calibration_id: sim_b21r_head, sim: {world: atlantis}}\n", "capture.sim.world"},
      {"capture: {source: sim, calibration_id: sim_b21r_head, sim: {noise_sigma: -1}}\n", "capture.sim.noise_sigma"},
  };
  for (const auto& [yaml, key] : cases) {
    SCOPED_TRACE(yaml);
    const auto cfg = config::Config::parse(yaml, "stereo_capture.yaml");
    try {
      load_capture_options(cfg.section("capture"), cfg.section("channels"), RGNAV_DATA_DIR, kConfigDir);
      ADD_FAILURE() << "accepted";
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("stereo_capture.yaml"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

// Pairs follow SIM_TRUTH: none before it, one per new true pose, stamped with its time and
// naming the calibration they were rendered through; bad truth is dropped and counted.
TEST(StereoCaptureSim, PublishesRenderedPairsAtTheTruePose)
{
  CaptureOptions o = shipped_sim_options();
  o.encoding = Encoding::kRaw;
  testing::FakeBusNode f("stereo_capture");
  sim::SimStereoFeed feed(*f.node, o, 0.26);
  StereoCaptureNode capture(*f.node, o, feed.take_source());

  capture.capture_once();
  EXPECT_EQ(capture.failures(), 1);  // no SIM_TRUTH yet
  EXPECT_TRUE(f.bus->published_on("STEREO_IMAGES").empty());

  const int64_t t0 = 1'000'000'000'000'000;
  f.node->publish("SIM_TRUTH", truth(t0 + 20'000, 20, 2, M_PI / 2));  // the office start, up the hallway
  capture.capture_once();
  capture.capture_once();  // no new truth: no second frame of the same instant
  EXPECT_EQ(capture.failures(), 2);
  f.node->publish("SIM_TRUTH", truth(t0 + 40'000, 20, 2.1, M_PI / 2));
  f.node->publish("SIM_TRUTH", truth(t0 + 30'000, 20, 2.1, M_PI / 2));  // back in time
  EXPECT_EQ(feed.truth_dropped(), 1);  // (a non-finite pose never leaves the bus: SimStereoSource test)
  capture.capture_once();

  const auto sent = testing::decoded<stereo_images_t>(*f.bus, "STEREO_IMAGES");
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(sent[0].utime, t0 + 20'000);
  EXPECT_EQ(sent[1].utime, t0 + 40'000);
  EXPECT_EQ(sent[1].frame_id, 2);
  for (const auto& m : sent) {
    EXPECT_EQ(m.calibration_id, "sim_b21r_head");
    const auto left = decode_image(m.left), right = decode_image(m.right);
    ASSERT_TRUE(left && right);
    EXPECT_EQ(left->size(), cv::Size(640, 480));
    EXPECT_GT(cv::norm(*left, *right, cv::NORM_L1), 0) << "two views";
  }
  // The robot moved 0.1 m: the images differ.
  EXPECT_GT(cv::norm(*decode_image(sent[0].left), *decode_image(sent[1].left), cv::NORM_L1) / (640 * 480 * 3), 2.0);
}

// The process: the shipped sim config passes --check-config; a misspelt key is refused naming
// file and key; with no simulator on the bus it runs (no frames: no SIM_TRUTH) and exits 0 on
// SIGTERM.
TEST(StereoCaptureSimProcess, CheckConfigRefusalAndCleanStop)
{
  using namespace std::chrono_literals;
  testing::TempDir dir("stereo_capture_sim");
  testing::ChildOptions o;
  o.stderr_path = dir.file("stderr");
  o.stdout_path = dir.file("stdout");
  auto status = testing::run_to_completion(
      {RGNAV_STEREO_CAPTURE_BIN, "--config", kConfigDir + "/stereo_capture_sim.yaml", "--check-config"}, 60s, o);
  EXPECT_TRUE(status.clean()) << status.describe() << testing::read_file(dir.file("stderr"));

  // A copy beside its own calibration file, the world named by path, one key misspelt.
  std::filesystem::create_directories(dir.file("stereo"));
  std::filesystem::copy_file(kConfigDir + "/stereo/sim_b21r_head.yml", dir.file("stereo/sim_b21r_head.yml"));
  std::string text = testing::read_file(kConfigDir + "/stereo_capture_sim.yaml");
  text.replace(text.find("world: office"), 13, "world: " + kConfigDir + "/worlds/office.yaml");
  const std::string good = text;
  text.replace(text.find("noise_seed"), 10, "noise_sed");
  testing::write_bytes(dir.file("bad.yaml"), text);
  status = testing::run_to_completion({RGNAV_STEREO_CAPTURE_BIN, "--config", dir.file("bad.yaml"), "--check-config"}, 60s, o);
  EXPECT_TRUE(status.exited && status.code == 2) << status.describe();
  const std::string err = testing::read_file(dir.file("stderr")) + testing::read_file(dir.file("stdout"));
  EXPECT_NE(err.find(dir.file("bad.yaml")), std::string::npos) << err;
  EXPECT_NE(err.find("capture.sim.noise_sed"), std::string::npos) << err;

  testing::write_bytes(dir.file("good.yaml"), good);
  testing::ChildProcess p({RGNAV_STEREO_CAPTURE_BIN, "--config", dir.file("good.yaml"), "--lcm-url", "memq://"}, o);
  const auto until = std::chrono::steady_clock::now() + 30s;
  while (std::chrono::steady_clock::now() < until &&
         testing::read_file(dir.file("stderr")).find("simulated stereo head") == std::string::npos)
    std::this_thread::sleep_for(50ms);
  ASSERT_TRUE(p.running()) << testing::read_file(dir.file("stderr"));
  std::this_thread::sleep_for(300ms);  // a few capture ticks without SIM_TRUTH
  ASSERT_TRUE(p.signal(SIGTERM));
  const auto stopped = p.wait_for(10s);
  ASSERT_TRUE(stopped.has_value()) << "still running 10 s after SIGTERM";
  EXPECT_TRUE(stopped->clean()) << stopped->describe() << testing::read_file(dir.file("stderr"));
}

TEST(SimStereoSource, NonFinitePoseOrOldTimeIgnored)
{
  const CaptureOptions o = shipped_sim_options();
  sim::SimStereoSource s(sim::load_world(o.sim.world_file), load_stereo_calibration(o.sim.calibration_file), {});
  EXPECT_FALSE(s.next());
  EXPECT_EQ(s.error(), "no SIM_TRUTH yet");
  EXPECT_FALSE(s.on_truth(10, {std::nan(""), 2, 0}));
  EXPECT_FALSE(s.next());
  EXPECT_TRUE(s.on_truth(10, {20, 2, 0}));
  EXPECT_FALSE(s.on_truth(10, {20, 2, 0}));
  EXPECT_FALSE(s.on_truth(20, {20, 2, std::numeric_limits<double>::infinity()}));
  const auto frame = s.next();
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->utime, 10);
  EXPECT_EQ(s.rendered(), 1);
  EXPECT_EQ(frame->left.type(), CV_8UC3);
  EXPECT_GT(cv::countNonZero(s.last().left.depth > 0), 0.99 * 640 * 480);

  sim::SimStereoSourceOptions grey;
  grey.grayscale = true;
  sim::SimStereoSource g(sim::load_world(o.sim.world_file), load_stereo_calibration(o.sim.calibration_file), grey);
  ASSERT_TRUE(g.on_truth(10, {20, 2, 0}));
  const auto gf = g.next();
  ASSERT_TRUE(gf);
  EXPECT_EQ(gf->left.type(), CV_8UC1);
  EXPECT_EQ(gf->right.size(), cv::Size(640, 480));
}

}  // namespace
}  // namespace rgnav::stereo
