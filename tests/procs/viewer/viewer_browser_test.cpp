// The page in a real browser: headless Chromium (Debian's chromium), driven over the DevTools
// protocol (headless_chromium.h), loads the page from the viewer node, which a fake publisher
// feeds with the two-room RG map and a robot driving through room_a (SLAM_POSE and laser scans
// every 50 ms). The page's state read back from its DOM must show both regions drawn, the door,
// the scan, and a robot that moved; a screenshot is kept in the build folder
// (viewer_browser.png). A second test clicks on room_b, answers the confirmation with yes, and
// expects the NAV_GOAL the planner takes. Skipped, saying so, when chromium is not installed.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "config/config.h"
#include "config/robot_description.h"
#include "fake_bus_node.h"
#include "headless_chromium.h"
#include "msg/conversions.h"
#include "rgmap/rgmap_conversions.h"
#include "rgnav/nav_goal_t.hpp"
#include "two_room_map.h"
#include "viewer/viewer_node.h"

namespace rgnav::viewer {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

std::string find_chromium()
{
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    for (const char* name : {"chromium", "chromium-browser"}) {
      const fs::path p = fs::path(dir) / name;
      if (::access(p.c_str(), X_OK) == 0) return p.string();
    }
  }
  return "";
}

// What the page mirrors into #state's data-* attributes.
constexpr const char* kState = "Object.assign({}, document.getElementById('state').dataset)";

class ViewerBrowser : public ::testing::Test
{
 protected:
  void SetUp() override
  {
    chromium_ = find_chromium();
    if (chromium_.empty()) GTEST_SKIP() << "chromium is not installed (apt-get install -y chromium): the browser test is skipped";
    out_dir_ = RGNAV_TEST_OUTPUT_DIR;
    fs::create_directories(out_dir_);
    profile_ = fs::temp_directory_path() / ("rgnav-viewer-chromium-" + std::to_string(::getpid()));
    const auto cfg = config::Config::parse("http: {port: 0}\nrates: {scan_hz: 20}\n", "browser_test.yaml");
    viewer_ = std::make_unique<ViewerNode>(*fb_.node, load_viewer_options(cfg, config::RobotDescription{}, RGNAV_VIEWER_WEB_ROOT),
                                           base_from_laser_);
    bus::publish(*fb_.bus, "RG_MAP", rgmap::to_msg(world_.map));
    drive_step();
    viewer_->flush();
  }
  void TearDown() override
  {
    viewer_.reset();
    std::error_code ec;
    if (!profile_.empty()) fs::remove_all(profile_, ec);
  }

  std::unique_ptr<testing::HeadlessChromium> open_page()
  {
    return std::make_unique<testing::HeadlessChromium>(chromium_, "http://127.0.0.1:" + std::to_string(viewer_->port()) + "/",
                                                       profile_, (out_dir_ / "viewer_browser_chromium.log").string());
  }

  // Drives the robot on and lets the viewer send, until `done(state)` or 20 s; returns the
  // newest state read from the page.
  json drive_until(testing::HeadlessChromium& page, const std::function<bool(const json&)>& done)
  {
    const auto deadline = Clock::now() + std::chrono::seconds(20);
    json state;
    while (Clock::now() < deadline) {
      drive_step();
      viewer_->flush();
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      state = page.evaluate(kState);
      if (done(state)) break;
    }
    return state;
  }

  // The robot one step further along room_a, facing +x, with the scan it sees there.
  void drive_step()
  {
    x_ = std::min(x_ + 0.02, 3.5);
    ++step_;
    const geometry::Pose2 map_from_base(x_, 1.5, 0.0);
    slam_pose_t p{};
    p.utime = step_ * 50'000;
    p.scan_id = step_;
    p.map_from_base = msg::to_msg(map_from_base);
    p.map_from_odom = msg::to_msg(geometry::Pose2());
    bus::publish(*fb_.bus, "SLAM_POSE", p);
    bus::publish(*fb_.bus, "LASER_FRONT", msg::to_msg(testing::cast_scan(world_.walls, map_from_base, base_from_laser_, p.utime, step_)));
  }

  static int number(const json& state, const char* key) { return state.contains(key) ? std::atoi(state[key].get<std::string>().c_str()) : -1; }

  std::string chromium_;
  fs::path out_dir_, profile_;
  testing::TwoRoomWorld world_ = testing::two_room_world();
  const geometry::Pose2 base_from_laser_{0.12, 0, 0};
  testing::FakeBusNode fb_{"viewer"};
  std::unique_ptr<ViewerNode> viewer_;
  double x_ = 1.0;
  int64_t step_ = 0;
};

TEST_F(ViewerBrowser, ThePageDrawsTheRegionsAndTheMovingRobot)
{
  auto page = open_page();
  // The first pose the page drew, then one well beyond it.
  const json first = drive_until(*page, [](const json& s) { return number(s, "poseUpdates") >= 1; });
  ASSERT_GE(number(first, "poseUpdates"), 1) << first.dump();
  const double x0 = std::atof(first["poseX"].get<std::string>().c_str());
  const json s = drive_until(*page, [&](const json& s) {
    return number(s, "regionsDrawn") == 2 && number(s, "scanPoints") > 10 && std::atof(s["poseX"].get<std::string>().c_str()) > x0 + 0.1;
  });
  EXPECT_EQ(s["connected"], "true");
  EXPECT_EQ(number(s, "regions"), 2);
  EXPECT_EQ(number(s, "regionsDrawn"), 2) << "both regions drawn on the canvas";
  EXPECT_EQ(number(s, "gateways"), 1);
  EXPECT_GT(number(s, "scanPoints"), 10);
  EXPECT_GT(std::atof(s["poseX"].get<std::string>().c_str()), x0 + 0.1) << "the robot drawn moved on from x = " << x0;
  EXPECT_EQ(s["poseY"], "1.5");
  EXPECT_EQ(page->evaluate("scene.map.regions.filter(r => r.freespace && r.freespace._image).length"), 2)
      << "the regions are painted from their freespace bitmaps";

  const fs::path png = out_dir_ / "viewer_browser.png";
  std::ofstream(png, std::ios::binary) << page->screenshot_png();
  std::ifstream shot(png, std::ios::binary);
  char magic[8] = {};
  shot.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG") << "a screenshot in " << png;
  EXPECT_EQ(viewer_->server_stats().closed_malformed, 0);
}

TEST_F(ViewerBrowser, AClickOnARegionSendsAGoalAfterConfirmation)
{
  auto page = open_page();
  drive_until(*page, [](const json& s) { return number(s, "regionsDrawn") == 2 && s["connected"] == "true"; });
  // Yes to the confirmation (a headless browser shows no dialog), then a real click in the
  // middle of room_b.
  page->evaluate("window.confirmed = 0; window.confirm = (q) => { window.confirmed++; window.question = q; return true; }; true");
  const json at = page->evaluate("toScreen(6.5, 1.0)");
  ASSERT_TRUE(at.is_array()) << at.dump();
  page->click(at[0].get<double>(), at[1].get<double>());
  const json s = drive_until(*page, [](const json& s) { return number(s, "goalsSent") >= 1; });
  EXPECT_EQ(number(s, "goalsSent"), 1);
  EXPECT_EQ(page->evaluate("window.confirmed"), 1) << "asked first";
  EXPECT_NE(page->evaluate("window.question").get<std::string>().find("room_b"), std::string::npos);
  // The page's acknowledgement, and the goal on the bus once the loop has run.
  const auto deadline = Clock::now() + std::chrono::seconds(10);
  while (Clock::now() < deadline && page->evaluate("document.getElementById('goal').textContent").get<std::string>() == "no goal")
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  viewer_->flush();
  EXPECT_EQ(page->evaluate("document.getElementById('goal').textContent"), "goal to region " + std::to_string(world_.room_b) + " sent");
  const auto goals = testing::decoded<nav_goal_t>(*fb_.bus, "NAV_GOAL");
  ASSERT_EQ(goals.size(), 1u);
  EXPECT_EQ(goals[0].region_id, world_.room_b);
  EXPECT_FALSE(goals[0].has_pose);
  EXPECT_FALSE(goals[0].cancel);
}

}  // namespace
}  // namespace rgnav::viewer
