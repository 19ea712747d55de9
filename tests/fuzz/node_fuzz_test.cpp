// The decode fuzz corruptions (type_fuzzer.h) through a runtime::Node subscription: corrupt
// buffers are dropped and counted, valid ones interleaved with them reach the handler
// unchanged, the heartbeat reports the drops; and semantic checks beyond the wire format.
#include "type_fuzzer.h"

namespace rgnav::testing {
namespace {

using namespace fuzz;

// Through a runtime::Node subscription: the same corrupt buffers are dropped and counted, valid
// ones interleaved with them reach the handler unchanged, and the heartbeat reports the drops.
template <class T>
void fuzz_node(const char* name)
{
  TypeFuzzer<T> f(name);
  f.run();
  runtime::NodeOptions options;
  options.name = "fuzz_node";
  auto fake = std::make_unique<bus::FakeBus>();
  bus::FakeBus* bus = fake.get();
  runtime::Node node(options, std::move(fake));
  std::vector<std::string> received;
  node.subscribe<T>("IN", [&](const T& msg) { received.push_back(to_json(msg)); });

  std::vector<std::string> expected;
  size_t next_valid = 0;
  for (size_t i = 0; i < f.must_reject().size(); ++i) {
    const auto& bad = f.must_reject()[i];
    bus->publish("IN", bad.data(), bad.size());
    if (i % 50 == 0) {
      const Bytes& good = f.valid()[next_valid++ % f.valid().size()];
      T decoded;
      std::string why;
      ASSERT_TRUE(bus::decode<T>(good.data(), good.size(), &decoded, &why)) << why;
      expected.push_back(to_json(decoded));
      bus->publish("IN", good.data(), good.size());
    }
  }
  EXPECT_EQ(received, expected) << name;
  EXPECT_EQ(node.drops().total(), static_cast<int64_t>(f.must_reject().size())) << name;
  EXPECT_EQ(node.drops().on_channel("IN"), static_cast<int64_t>(f.must_reject().size())) << name;
  EXPECT_EQ(node.messages_in(), static_cast<int64_t>(expected.size())) << name;

  node.publish_heartbeat();
  const auto beats = bus->published_on("HEARTBEAT");
  ASSERT_FALSE(beats.empty());
  heartbeat_t hb;
  std::string why;
  ASSERT_TRUE(bus::decode<heartbeat_t>(beats.back().data.data(), beats.back().data.size(), &hb, &why)) << why;
  EXPECT_EQ(hb.messages_dropped, static_cast<int64_t>(f.must_reject().size()));
  EXPECT_EQ(hb.messages_in, static_cast<int64_t>(expected.size()));
}

#define RGNAV_NODE_TEST(T) \
  TEST(NodeSubscriptionFuzz, T) { fuzz_node<T>(#T); }
RGNAV_FOR_EACH_MESSAGE_TYPE(RGNAV_NODE_TEST)
#undef RGNAV_NODE_TEST

// Semantic checks (msg::semantically_valid) beyond the wire format, through a subscription:
// encoded with lcm-gen directly, as a buggy or hostile sender would.
template <class T>
Bytes raw_encode(const T& msg)
{
  Bytes b(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

TEST(NodeSubscriptionFuzz, SemanticallyInvalidMessagesAreDroppedAndCounted)
{
  runtime::NodeOptions options;
  options.name = "semantic";
  auto fake = std::make_unique<bus::FakeBus>();
  bus::FakeBus* bus = fake.get();
  runtime::Node node(options, std::move(fake));
  int scans = 0, images = 0, cmds = 0, grids = 0, goals = 0, trajectories = 0, regions = 0;
  node.subscribe<laser_scan_t>("SCAN", [&](const laser_scan_t&) { ++scans; });
  node.subscribe<image_t>("IMAGE", [&](const image_t&) { ++images; });
  node.subscribe<velocity_cmd_t>("CMD", [&](const velocity_cmd_t&) { ++cmds; });
  node.subscribe<obstacle_grid_t>("GRID", [&](const obstacle_grid_t&) { ++grids; });
  node.subscribe<nav_goal_t>("GOAL", [&](const nav_goal_t&) { ++goals; });
  node.subscribe<trajectory_t>("TRAJ", [&](const trajectory_t&) { ++trajectories; });
  node.subscribe<region_t>("REGION", [&](const region_t&) { ++regions; });

  std::vector<std::pair<std::string, Bytes>> bad;
  {
    auto m = sample<laser_scan_t>(0);
    m.scan_id = 0;
    bad.push_back({"SCAN", raw_encode(m)});
    m = sample<laser_scan_t>(0);
    m.ranges[5] = -1.f;
    bad.push_back({"SCAN", raw_encode(m)});
    m = sample<laser_scan_t>(0);
    m.nintensities = 3;
    m.intensities.assign(3, 1.f);
    bad.push_back({"SCAN", raw_encode(m)});
    m = sample<laser_scan_t>(0);
    m.angle_increment = 0.1f;  // 181 beams over 18 rad
    bad.push_back({"SCAN", raw_encode(m)});
  }
  {
    auto m = sample<image_t>(0);
    m.height += 1;  // size no longer row_stride * height
    bad.push_back({"IMAGE", raw_encode(m)});
    m = sample<image_t>(2);  // JPEG without SOI marker
    m.data[0] = 0;
    bad.push_back({"IMAGE", raw_encode(m)});
  }
  {
    auto m = sample<velocity_cmd_t>(0);
    m.v = 50;
    bad.push_back({"CMD", raw_encode(m)});
    m = sample<velocity_cmd_t>(0);
    m.deadline_us = 0;
    bad.push_back({"CMD", raw_encode(m)});
  }
  {
    auto m = sample<obstacle_grid_t>(1);
    m.cells.assign(m.cells.size(), 101);
    if (!m.cells.empty()) bad.push_back({"GRID", raw_encode(m)});
  }
  {
    auto m = sample<nav_goal_t>(0);
    m.position_tolerance = 0;
    bad.push_back({"GOAL", raw_encode(m)});
  }
  {
    auto m = sample<trajectory_t>(0);
    m.a_max = -1;
    bad.push_back({"TRAJ", raw_encode(m)});
  }
  {
    auto m = sample<region_t>(0);
    m.freespace_nbytes += 1;
    m.freespace.push_back(0);
    bad.push_back({"REGION", raw_encode(m)});
  }
  for (const auto& [channel, bytes] : bad) bus->publish(channel, bytes.data(), bytes.size());
  EXPECT_EQ(scans + images + cmds + grids + goals + trajectories + regions, 0);
  EXPECT_EQ(node.drops().total(), static_cast<int64_t>(bad.size()));
  EXPECT_EQ(node.drops().on_channel("SCAN"), 4);

  // The valid originals still pass.
  for (auto [channel, bytes] : std::vector<std::pair<std::string, Bytes>>{
           {"SCAN", raw_encode(sample<laser_scan_t>(0))}, {"IMAGE", raw_encode(sample<image_t>(2))},
           {"CMD", raw_encode(sample<velocity_cmd_t>(0))}, {"GOAL", raw_encode(sample<nav_goal_t>(0))}})
    bus->publish(channel, bytes.data(), bytes.size());
  EXPECT_EQ(scans, 1);
  EXPECT_EQ(images, 1);
  EXPECT_EQ(cmds, 1);
  EXPECT_EQ(goals, 1);
  EXPECT_EQ(node.drops().total(), static_cast<int64_t>(bad.size()));
}

}  // namespace
}  // namespace rgnav::testing
