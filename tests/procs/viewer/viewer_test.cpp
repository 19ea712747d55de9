// The viewer's library without a network: the scene's JSON frames (all in the map frame, only
// what changed, the map throttled), the per-client bounded queue and what a page may send.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>

#include "viewer/client_input.h"
#include "viewer/frame_queue.h"
#include "viewer/scene.h"
#include "viewer/stream_rates.h"

namespace rgnav::viewer {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

// Two regions side by side: region 1 at the origin, region 2 four metres along x, one door.
rgmap::RgMap two_rooms()
{
  rgmap::RgMap map;
  auto& a = map.add_region(geometry::Pose2(0, 0, 0), 1);
  a.name = "lab";
  a.segments.push_back({{0, 0}, {4, 0}, 0.01, 10});
  a.bbox_min = {0, 0};
  a.bbox_max = {4, 3};
  auto& b = map.add_region(geometry::Pose2(4, 0, M_PI / 2), 2);
  b.segments.push_back({{0, 0}, {1, 0}, 0.01, 10});   // along the map's y in the map frame
  b.bbox_min = {0, 0};
  b.bbox_max = {3, 3};
  auto& g = map.add_gateway(rgmap::GatewayClass::kDoor, a.id, 2);
  g.gateway_points = {{4, 1}, {4, 2}};
  map.connect(g.id, b.id, geometry::Pose2(4, 0, M_PI / 2));
  map.version = 7;
  return map;
}

const json* find_frame(const std::vector<Frame>& frames, const std::string& topic, json* out)
{
  for (const auto& f : frames) {
    if (f.topic == topic) {
      *out = json::parse(f.text);
      return out;
    }
  }
  return nullptr;
}

TEST(ViewerScene, MapFrameHasRegionsInTheMapFrameWithNamesAndGatewayClasses)
{
  Scene scene({});
  scene.set_map(two_rooms());
  const json m = scene.map_json();
  EXPECT_EQ(m["type"], "map");
  EXPECT_EQ(m["version"], 7);
  ASSERT_EQ(m["regions"].size(), 2u);
  EXPECT_EQ(m["regions"][0]["name"], "lab");
  // Region 2's segment (0,0)-(1,0) in its frame lies along the map's y from (4,0).
  const json seg = m["regions"][1]["segments"][0];
  EXPECT_NEAR(seg[0].get<double>(), 4.0, 1e-3);
  EXPECT_NEAR(seg[2].get<double>(), 4.0, 1e-3);
  EXPECT_NEAR(seg[3].get<double>(), 1.0, 1e-3);
  ASSERT_EQ(m["gateways"].size(), 1u);
  EXPECT_EQ(m["gateways"][0]["class_name"], std::string(rgmap::to_string(rgmap::GatewayClass::kDoor)));
  EXPECT_EQ(m["gateways"][0]["lines"].size(), 1u);
}

TEST(ViewerScene, FreespaceGoesAsItsBitsWithTheGridsFrameInTheMap)
{
  auto map = two_rooms();
  // 10 x 3 cells of 0.1 m at (0.5, 0.5) of region 2; cell (0, 0) and (9, 2) free.
  rgmap::FreespaceBitmap f(0.1, geometry::Pose2(0.5, 0.5, 0), 10, 3);
  f.set_free(0, 0, true);
  f.set_free(9, 2, true);
  map.region(2)->freespace = f;
  Scene scene({});
  scene.set_map(map);
  const json fs = scene.map_json()["regions"][1]["freespace"];
  EXPECT_EQ(fs["width"], 10);
  EXPECT_EQ(fs["height"], 3);
  // Region 2's frame is (4, 0, 90 deg): the grid's corner at (4 - 0.5, 0.5).
  EXPECT_NEAR(fs["frame"][0].get<double>(), 3.5, 1e-3);
  EXPECT_NEAR(fs["frame"][1].get<double>(), 0.5, 1e-3);
  // 30 bits = 4 bytes: bit 0 and bit 29 set -> 0x01 0x00 0x00 0x20 -> "AQAAIA==".
  EXPECT_EQ(fs["bits"], "AQAAIA==");
  EXPECT_TRUE(scene.map_json()["regions"][0]["freespace"].is_null()) << "a region without a bitmap";
}

TEST(ViewerScene, MergedRegionsAreNotDrawnTwice)
{
  auto map = two_rooms();
  map.region(2)->state = rgmap::Region::State::kMerged;
  map.region(2)->merged_into = 1;
  Scene scene({});
  scene.set_map(map);
  EXPECT_EQ(scene.map_json()["regions"].size(), 1u);
}

TEST(ViewerScene, ScanTargetsAndTrajectoryArePlacedThroughTheNewestPose)
{
  Scene scene({});
  EXPECT_TRUE(scene.scan_json().is_null()) << "no scan yet";
  RobotPoseView pose;
  pose.utime = 10;
  pose.source = "SLAM_POSE";
  pose.map_from_base = geometry::Pose2(1, 2, M_PI / 2);
  pose.map_from_odom = geometry::Pose2(10, 0, 0);
  scene.set_pose(pose);
  scene.set_scan({11, {{1.0, 0.0}}});
  const json scan = scene.scan_json();
  ASSERT_EQ(scan["points"].size(), 2u);
  // One metre ahead of a robot at (1,2) facing +y.
  EXPECT_NEAR(scan["points"][0].get<double>(), 1.0, 1e-3);
  EXPECT_NEAR(scan["points"][1].get<double>(), 3.0, 1e-3);
  scene.set_targets({12, 5, {geometry::Pose2(1, 1, 0)}});
  const json t = scene.targets_json();
  EXPECT_NEAR(t["targets"][0][0].get<double>(), 11.0, 1e-3);
  EXPECT_EQ(t["goal_id"], 5);
  scene.set_trajectory({13, {{0, 0}, {1, 0}}});
  EXPECT_NEAR(scene.trajectory_json()["points"][2].get<double>(), 11.0, 1e-3);
  EXPECT_EQ(scene.pose_json()["source"], "SLAM_POSE");
}

TEST(ViewerScene, PathWaypointsGoThroughTheirRegionsFrames)
{
  Scene scene({});
  scene.set_map(two_rooms());
  PathView p;
  p.goal_id = 3;
  p.status = 0;
  p.waypoints = {{1, 0, geometry::Pose2(1, 1, 0)}, {2, 0, geometry::Pose2(1, 0, 0)}};
  scene.set_path(p);
  const json j = scene.path_json();
  ASSERT_EQ(j["points"].size(), 4u);
  EXPECT_NEAR(j["points"][2].get<double>(), 4.0, 1e-3);
  EXPECT_NEAR(j["points"][3].get<double>(), 1.0, 1e-3);
  EXPECT_EQ(j["status_name"], "on the way");
}

TEST(ViewerScene, OnlyChangedTopicsAreSentAndTheMapAtMostOncePerPeriod)
{
  SceneOptions o;
  o.map_period = std::chrono::milliseconds(1000);
  o.status_period = std::chrono::milliseconds(1000);
  Scene scene(o);
  const auto t0 = Clock::now();
  scene.set_map(two_rooms());
  RobotPoseView pose;
  scene.set_pose(pose);
  auto frames = scene.take_changed(t0, 0);
  json j;
  EXPECT_TRUE(find_frame(frames, "map", &j));
  EXPECT_TRUE(find_frame(frames, "pose", &j));
  EXPECT_TRUE(find_frame(frames, "rates", &j));
  // Nothing changed: nothing but what time alone changes, and that only once a period.
  EXPECT_TRUE(scene.take_changed(t0 + std::chrono::milliseconds(10), 0).empty());
  // A new map 100 ms later waits for its period; a pose goes out at once.
  scene.set_map(two_rooms());
  scene.set_pose(pose);
  frames = scene.take_changed(t0 + std::chrono::milliseconds(100), 0);
  EXPECT_FALSE(find_frame(frames, "map", &j));
  EXPECT_TRUE(find_frame(frames, "pose", &j));
  frames = scene.take_changed(t0 + std::chrono::milliseconds(1000), 0);
  EXPECT_TRUE(find_frame(frames, "map", &j)) << "held back, not lost";
}

TEST(ViewerScene, ProcessTableRaisesAlerts)
{
  Scene scene({});
  SupervisorView s;
  s.host = "robot";
  ProcessRow ok, hung;
  ok.name = "planner";
  ok.state = 2;
  hung.name = "lld";
  hung.state = 3;
  s.processes = {ok, hung};
  scene.set_supervisor(s);
  HeartbeatView beat;
  beat.name = "rg_kernel";
  beat.utime = 1'000'000;
  beat.state = 1;
  scene.add_heartbeat(beat);
  const json fresh = scene.processes_json(1'500'000);
  ASSERT_EQ(fresh["alerts"].size(), 1u);
  EXPECT_EQ(fresh["alerts"][0], "lld hung");
  EXPECT_EQ(fresh["processes"][1]["state"], "hung");
  const json stale = scene.processes_json(10'000'000);
  EXPECT_EQ(stale["alerts"].size(), 2u) << stale.dump();
}

TEST(ViewerScene, HeartbeatNamesAreBounded)
{
  SceneOptions o;
  o.max_heartbeat_names = 3;
  Scene scene(o);
  for (int i = 0; i < 10; ++i) {
    HeartbeatView b;
    b.name = "p" + std::to_string(i);
    scene.add_heartbeat(b);
  }
  EXPECT_EQ(scene.processes_json(0)["heartbeats"].size(), 3u);
}

TEST(ViewerStreamRates, RateFromArrivalsAndZeroOnceStopped)
{
  StreamRates rates(std::chrono::seconds(5));
  const auto t0 = Clock::now();
  for (int i = 0; i <= 10; ++i) rates.note("SLAM_POSE", i, t0 + std::chrono::milliseconds(100 * i));
  auto r = rates.rates(t0 + std::chrono::seconds(1));
  ASSERT_EQ(r.size(), 1u);
  EXPECT_NEAR(r[0].hz, 10.0, 1e-6);
  EXPECT_EQ(r[0].count, 11);
  r = rates.rates(t0 + std::chrono::seconds(20));
  EXPECT_EQ(r[0].hz, 0.0);
  EXPECT_NEAR(r[0].age_s, 19.0, 1e-6);
}

SharedFrame frame(const std::string& topic, const std::string& text)
{
  return {topic, std::make_shared<const std::string>(text)};
}

TEST(ViewerFrameQueue, ANewerFrameReplacesTheQueuedOneOfItsTopicInPlace)
{
  FrameQueue q(4);
  q.push(frame("map", "m1"));
  q.push(frame("pose", "p1"));
  q.push(frame("pose", "p2"));
  EXPECT_EQ(q.size(), 2u);
  EXPECT_EQ(q.dropped(), 1);
  EXPECT_EQ(*q.pop()->text, "m1") << "the map keeps its turn";
  EXPECT_EQ(*q.pop()->text, "p2");
  EXPECT_FALSE(q.pop());
}

TEST(ViewerFrameQueue, ASlowClientsQueueStaysBoundedAndKeepsTheNewestOfEveryTopic)
{
  FrameQueue q(12);
  const std::vector<std::string> topics = {"map", "pose", "scan", "targets", "path", "rates"};
  for (int i = 0; i < 10000; ++i) q.push(frame(topics[i % topics.size()], std::to_string(i)));
  EXPECT_EQ(q.size(), topics.size());
  EXPECT_EQ(q.dropped(), 10000 - static_cast<int64_t>(topics.size()));
  std::set<std::string> seen;
  while (auto f = q.pop()) {
    seen.insert(f->topic);
    EXPECT_GE(std::stoi(*f->text), 10000 - static_cast<int>(topics.size()));
  }
  EXPECT_EQ(seen.size(), topics.size());
}

TEST(ViewerFrameQueue, WhenFullTheOldestFrameGoes)
{
  FrameQueue q(2);
  q.push(frame("a", "1"));
  q.push(frame("b", "2"));
  q.push(frame("c", "3"));
  EXPECT_EQ(q.size(), 2u);
  EXPECT_EQ(*q.pop()->text, "2");
}

TEST(ViewerClientInput, GoalsAndCancelsParse)
{
  std::string why;
  auto g = parse_client_input(R"({"type":"goal","region_id":3})", &why);
  ASSERT_TRUE(g) << why;
  EXPECT_EQ(g->region_id, 3);
  EXPECT_FALSE(g->region_pose);
  g = parse_client_input(R"({"type":"goal","region_id":3,"pose":[1,2,0.5],"token":"x"})", &why);
  ASSERT_TRUE(g) << why;
  ASSERT_TRUE(g->region_pose);
  EXPECT_DOUBLE_EQ(g->region_pose->y(), 2.0);
  EXPECT_EQ(g->token, "x");
  g = parse_client_input(R"({"type":"cancel"})", &why);
  ASSERT_TRUE(g) << why;
  EXPECT_TRUE(g->cancel);
}

TEST(ViewerClientInput, MalformedInputIsRefused)
{
  for (const char* bad : {"", "not json", "[1,2]", "{}", R"({"type":"shutdown"})", R"({"type":"goal"})",
                          R"({"type":"goal","region_id":-1})", R"({"type":"goal","region_id":1.5})",
                          R"({"type":"goal","region_id":"1"})", R"({"type":"goal","region_id":1,"extra":1})",
                          R"({"type":"goal","region_id":1,"pose":[1,2]})", R"({"type":"goal","region_id":1,"pose":[1,2,1e300]})",
                          R"({"type":"cancel","token":5})"}) {
    std::string why;
    EXPECT_FALSE(parse_client_input(bad, &why)) << bad;
    EXPECT_FALSE(why.empty()) << bad;
  }
}

TEST(ViewerClientInput, GoalsFromOtherHostsNeedTheToken)
{
  GoalRequest r;
  std::string why;
  EXPECT_TRUE(goal_allowed(r, true, "", &why));
  EXPECT_FALSE(goal_allowed(r, false, "", &why)) << "no token configured: off";
  r.token = "wrong-token-0000";
  EXPECT_FALSE(goal_allowed(r, false, "right-token-0000", &why));
  r.token = "right-token-0000";
  EXPECT_TRUE(goal_allowed(r, false, "right-token-0000", &why));
}

}  // namespace
}  // namespace rgnav::viewer
