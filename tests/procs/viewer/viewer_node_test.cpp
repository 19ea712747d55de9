// The viewer's node over a FakeBus on the two-room map: messages become the scene, POSE is
// preferred over SLAM_POSE while fresh, a map the model refuses is dropped and counted, a goal
// sent by a page over a real socket goes out on NAV_GOAL from the loop, and config/viewer.yaml
// is read and bad values are refused naming the file and key.
#include <gtest/gtest.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <thread>

#include <unistd.h>

#include "child_process.h"
#include "config/config.h"
#include "config/robot_description.h"
#include "fake_bus_node.h"
#include "msg/conversions.h"
#include "rgmap/rgmap_conversions.h"
#include "rgnav/nav_goal_t.hpp"
#include "two_room_map.h"
#include "viewer/viewer_node.h"

namespace rgnav::viewer {
namespace {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;

ViewerOptions test_options()
{
  const auto cfg = config::Config::parse("http: {port: 0}\n", "test.yaml");
  return load_viewer_options(cfg, config::RobotDescription{}, RGNAV_VIEWER_WEB_ROOT);
}

slam_pose_t slam_pose(double x, double y, int64_t utime)
{
  slam_pose_t m{};
  m.utime = utime;
  m.map_from_base = msg::to_msg(geometry::Pose2(x, y, 0));
  m.map_from_odom = msg::to_msg(geometry::Pose2());
  return m;
}

TEST(ViewerNode, MapAndPoseBecomeTheScene)
{
  testing::FakeBusNode fb("viewer");
  ViewerNode viewer(*fb.node, test_options(), geometry::Pose2(0.12, 0, 0), /*serve=*/false);
  bus::publish(*fb.bus, "RG_MAP", rgmap::to_msg(testing::two_room_world().map));
  bus::publish(*fb.bus, "SLAM_POSE", slam_pose(1, 1, 100));
  EXPECT_EQ(viewer.scene().map_json()["regions"].size(), 2u);
  EXPECT_EQ(viewer.scene().pose_json()["source"], "SLAM_POSE");

  region_pose_t pose{};
  pose.utime = 200;
  pose.region_id = 2;
  pose.map_from_base = msg::to_msg(geometry::Pose2(5, 1, 0));
  pose.region_from_base = msg::to_msg(geometry::Pose2(1, 1, 0));
  bus::publish(*fb.bus, "POSE", pose);
  bus::publish(*fb.bus, "SLAM_POSE", slam_pose(1, 1, 300));
  EXPECT_EQ(viewer.scene().pose_json()["source"], "POSE") << "the localizer's pose is preferred while fresh";
  EXPECT_EQ(viewer.scene().pose_json()["region_id"], 2);
}

TEST(ViewerNode, AMapTheModelRefusesIsDroppedAndCounted)
{
  testing::FakeBusNode fb("viewer");
  ViewerNode viewer(*fb.node, test_options(), geometry::Pose2(), false);
  auto m = rgmap::to_msg(testing::two_room_world().map);
  m.regions[1].id = m.regions[0].id;   // two regions with one id
  const int64_t before = fb.node->drops().total();
  bus::publish(*fb.bus, "RG_MAP", m);
  EXPECT_EQ(fb.node->drops().total(), before + 1);
  EXPECT_EQ(viewer.scene().map_json()["regions"].size(), 0u);
}

TEST(ViewerNode, AGoalFromAPageGoesOutOnNavGoal)
{
  testing::FakeBusNode fb("viewer");
  ViewerNode viewer(*fb.node, test_options(), geometry::Pose2(), true);
  ASSERT_GT(viewer.port(), 0);
  net::io_context ioc;
  websocket::stream<tcp::socket> ws(ioc);
  tcp::resolver resolver(ioc);
  net::connect(ws.next_layer(), resolver.resolve("127.0.0.1", std::to_string(viewer.port())));
  ws.handshake("127.0.0.1", "/ws");
  ws.write(net::buffer(std::string(R"({"type":"goal","region_id":2,"pose":[1,0.5,0]})")));
  // The acknowledgement comes after the goal was queued for the loop.
  for (;;) {
    beast::flat_buffer b;
    ws.read(b);
    if (nlohmann::json::parse(beast::buffers_to_string(b.data()))["type"] == "goal_ack") break;
  }
  EXPECT_TRUE(fb.bus->published_on("NAV_GOAL").empty()) << "the server thread never publishes";
  viewer.flush();
  const auto goals = testing::decoded<nav_goal_t>(*fb.bus, "NAV_GOAL");
  ASSERT_EQ(goals.size(), 1u);
  EXPECT_EQ(goals[0].region_id, 2);
  EXPECT_TRUE(goals[0].has_pose);
  EXPECT_DOUBLE_EQ(goals[0].region_from_goal.y, 0.5);
  EXPECT_FALSE(goals[0].cancel);
  EXPECT_GT(goals[0].goal_id, 0);
}

TEST(ViewerNode, TheShippedConfigLoadsAndBadValuesAreRefusedByName)
{
  const auto robot = config::RobotDescription{};
  const auto shipped = config::Config::load(std::string(RGNAV_SOURCE_DIR) + "/config/viewer.yaml");
  const auto o = load_viewer_options(shipped, robot, "web");
  EXPECT_EQ(runtime::load_node_options(shipped.section("node"), "viewer").name, "viewer");
  shipped.finish();
  EXPECT_EQ(o.server.address, "127.0.0.1") << "loopback by default";
  EXPECT_TRUE(o.server.goal_token.empty());
  EXPECT_EQ(o.server.web_root, "web");

  auto refused = [&](const std::string& yaml, const std::string& key) {
    try {
      const auto cfg = config::Config::parse(yaml, "viewer.yaml");
      load_viewer_options(cfg, robot, "web");
      cfg.finish();
      ADD_FAILURE() << yaml << " accepted";
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("viewer.yaml"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  refused("http: {address: localhost-ish}\n", "http.address");
  refused("http: {port: 70000}\n", "http.port");
  refused("http: {goal_token: short}\n", "http.goal_token");
  refused("http: {queue_frames: 2}\n", "http.queue_frames");
  refused("rates: {frame_hz: 0}\n", "rates.frame_hz");
  refused("http: {prot: 80}\n", "http.prot");
}

// The process: --check-config binds nothing; started, it prints its address, serves the page
// and stops cleanly on SIGTERM.
TEST(ViewerProcess, ServesThePageAndStopsCleanly)
{
  const std::string config = std::string(RGNAV_SOURCE_DIR) + "/config/viewer.yaml";
  {
    testing::ChildProcess check({RGNAV_VIEWER_BIN, "--config", config, "--check-config"});
    const auto status = check.wait_for(std::chrono::seconds(20));
    ASSERT_TRUE(status);
    EXPECT_TRUE(status->clean()) << status->describe();
  }
  const std::string out = (std::filesystem::temp_directory_path() / ("rgnav-viewer-" + std::to_string(::getpid()) + ".out")).string();
  testing::ChildOptions co;
  co.stdout_path = out;
  co.stderr_path = out + ".err";
  testing::ChildProcess viewer({RGNAV_VIEWER_BIN, "--config", config, "--port", "0", "--lcm-url", "memq://"}, co);
  std::string line;
  for (int i = 0; i < 200 && line.rfind("viewer: http://", 0) != 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::ifstream in(out);
    std::getline(in, line);
  }
  ASSERT_EQ(line.rfind("viewer: http://127.0.0.1:", 0), 0u) << "no address printed: '" << line << "'";
  const std::string port = line.substr(std::string("viewer: http://127.0.0.1:").size(), line.size() - 1 - std::string("viewer: http://127.0.0.1:").size());
  net::io_context ioc;
  websocket::stream<tcp::socket> ws(ioc);
  tcp::resolver resolver(ioc);
  net::connect(ws.next_layer(), resolver.resolve("127.0.0.1", port));
  ws.handshake("127.0.0.1", "/ws");
  beast::flat_buffer b;
  ws.read(b);
  EXPECT_EQ(nlohmann::json::parse(beast::buffers_to_string(b.data()))["type"], "hello");
  testing::expect_clean_stop(viewer);
  std::filesystem::remove(out);
  std::filesystem::remove(out + ".err");
}

}  // namespace
}  // namespace rgnav::viewer
