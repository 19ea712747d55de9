#include "runtime/node.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <thread>

#include "bus/fake_bus.h"
#include "bus/lcm_bus.h"
#include "rgnav/heartbeat_t.hpp"
#include "rgnav/odometry_t.hpp"

namespace rgnav::runtime {
namespace {

struct NodeFixture : ::testing::Test
{
  NodeFixture()
  {
    auto b = std::make_unique<bus::FakeBus>();
    fake = b.get();
    NodeOptions o;
    o.name = "unit";
    o.input_stale_after = std::chrono::milliseconds(20);
    node = std::make_unique<Node>(o, std::move(b));
  }

  heartbeat_t last_heartbeat()
  {
    const auto hbs = fake->published_on("HEARTBEAT");
    EXPECT_FALSE(hbs.empty());
    heartbeat_t hb;
    std::string why;
    EXPECT_TRUE(bus::decode(hbs.back().data.data(), hbs.back().data.size(), &hb, &why)) << why;
    return hb;
  }

  void send_odometry(int64_t utime)
  {
    odometry_t o{};
    o.utime = utime;
    o.status = odometry_t::STATUS_OK;
    ASSERT_TRUE(bus::publish(*fake, "ODOMETRY", o));
  }

  bus::FakeBus* fake = nullptr;
  std::unique_ptr<Node> node;
};

TEST_F(NodeFixture, HeartbeatFieldsAndStates)
{
  node->subscribe<odometry_t>("ODOMETRY", [](const odometry_t&) {});
  node->publish_heartbeat();
  auto hb = last_heartbeat();
  EXPECT_EQ(hb.name, "unit");
  EXPECT_EQ(hb.pid, getpid());
  EXPECT_EQ(hb.seq, 1);
  EXPECT_EQ(hb.state, heartbeat_t::STATE_STARTING);
  EXPECT_EQ(hb.last_input_age_us, -1);
  EXPECT_GT(hb.rss_kb, 0);

  send_odometry(1000);
  node->publish_heartbeat();
  hb = last_heartbeat();
  EXPECT_EQ(hb.seq, 2);
  EXPECT_EQ(hb.state, heartbeat_t::STATE_RUNNING);
  EXPECT_GE(hb.last_input_age_us, 0);
  EXPECT_EQ(hb.messages_in, 1);

  std::this_thread::sleep_for(std::chrono::milliseconds(40));
  node->publish_heartbeat();
  EXPECT_EQ(last_heartbeat().state, heartbeat_t::STATE_DEGRADED);

  node->set_status(heartbeat_t::STATE_DEGRADED, "laser CRC errors");
  node->publish_heartbeat();
  EXPECT_EQ(last_heartbeat().status, "laser CRC errors");
}

TEST_F(NodeFixture, MalformedInputCountedInHeartbeat)
{
  int delivered = 0;
  node->subscribe<odometry_t>("ODOMETRY", [&](const odometry_t&) { ++delivered; });
  const uint8_t junk[] = {0xde, 0xad, 0xbe, 0xef};
  fake->publish("ODOMETRY", junk, sizeof junk);
  send_odometry(5);
  node->publish_heartbeat();
  const auto hb = last_heartbeat();
  EXPECT_EQ(delivered, 1);
  EXPECT_EQ(hb.messages_dropped, 1);
  EXPECT_EQ(hb.messages_in, 1);
}

TEST_F(NodeFixture, MessageClockFollowsInputs)
{
  node->subscribe<odometry_t>("ODOMETRY", [](const odometry_t&) {});
  send_odometry(2'000'000);
  send_odometry(1'000'000);  // older: must not move the clock back
  EXPECT_EQ(time::to_utime(node->clock().now()), 2'000'000);
}

TEST_F(NodeFixture, MessageTimersFireOnMessageTimeMultiples)
{
  std::vector<int64_t> fired;
  node->every_message_time(std::chrono::seconds(1), [&](time::Time t) { fired.push_back(time::to_utime(t)); });
  node->subscribe<odometry_t>("ODOMETRY", [](const odometry_t&) {});
  for (int64_t t = 500'000; t <= 3'600'000; t += 100'000) send_odometry(t);
  // Aligned to whole seconds: first input starts the timer, then fires at 1 s, 2 s, 3 s.
  EXPECT_EQ(fired, (std::vector<int64_t>{1'000'000, 2'000'000, 3'000'000}));
}

TEST_F(NodeFixture, WallTimersRunFromSpin)
{
  int ticks = 0;
  node->every(std::chrono::milliseconds(5), [&] { ++ticks; });
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(60);
  while (std::chrono::steady_clock::now() < end) node->spin_once(std::chrono::milliseconds(5));
  EXPECT_GE(ticks, 3);
}

TEST_F(NodeFixture, SigtermStopsRunCleanly)
{
  // SIGTERM is blocked while a Node exists, so raise() leaves it pending for the signalfd.
  ASSERT_EQ(raise(SIGTERM), 0);
  EXPECT_EQ(node->run(), 0);
  EXPECT_TRUE(node->stop_requested());
  EXPECT_EQ(last_heartbeat().state, heartbeat_t::STATE_STOPPING);
}

TEST_F(NodeFixture, HeartbeatTimerAtConfiguredRate)
{
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(450);
  while (std::chrono::steady_clock::now() < end) node->spin_once(std::chrono::milliseconds(10));
  // 5 Hz over 0.45 s: two timer heartbeats (loose bound, no timing flake on a loaded machine).
  EXPECT_GE(fake->published_on("HEARTBEAT").size(), 1u);
  EXPECT_LE(fake->published_on("HEARTBEAT").size(), 3u);
}

// A synchronous bus delivers a heartbeat to this node's own handler while it is being sent
// (the supervisor hears HEARTBEAT and beats itself): no lock may be held across the publish.
TEST_F(NodeFixture, OwnHeartbeatIsHandledOnASynchronousBus)
{
  int heard = 0;
  node->subscribe<heartbeat_t>("HEARTBEAT", [&](const heartbeat_t& hb) { heard += hb.name == "unit"; });
  node->publish_heartbeat();
  EXPECT_EQ(heard, 1);
  EXPECT_EQ(node->messages_in(), 1);
}

// Long work in a handler: the heartbeat goes on beside the loop, says how long the loop has
// been busy, and its progress counter moves on only while the work reports steps.
TEST(NodeHeartbeatBesideTheLoop, BeatsThroughLongWorkAndCountsItsProgress)
{
  NodeOptions o;
  o.name = "worker";
  o.heartbeat_hz = 20.0;
  Node node(o, std::make_unique<bus::LcmBus>("memq://"));
  std::vector<heartbeat_t> beats;
  node.subscribe<heartbeat_t>("HEARTBEAT", [&](const heartbeat_t& hb) { beats.push_back(hb); });
  int64_t progress_before = 0, progress_after_steps = 0;
  int turns_after = 0;
  node.every(std::chrono::milliseconds(50), [&] {
    // The beats sent meanwhile are handled on the turns after the work.
    if (progress_before != 0) {
      if (++turns_after == 4) node.request_stop();
      return;
    }
    progress_before = node.progress();
    // 400 ms of work in steps that report progress, then 400 ms stuck without a report.
    for (int i = 0; i < 8; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      node.note_progress();
    }
    progress_after_steps = node.progress();
    std::this_thread::sleep_for(std::chrono::milliseconds(400));
  });
  const char junk[] = "not a heartbeat";
  ASSERT_TRUE(node.bus().publish("HEARTBEAT", junk, sizeof junk));
  ASSERT_EQ(node.run(), 0);
  EXPECT_EQ(progress_after_steps - progress_before, 8);
  ASSERT_FALSE(beats.empty());
  EXPECT_EQ(beats.back().messages_dropped, 1) << "the loop's drop count reaches the beats sent beside it";
  // Beats sent while the loop was stuck in the handler: busy, and the progress they carry
  // never passes what the handler reported.
  int busy = 0;
  for (const auto& hb : beats) {
    if (hb.busy_ms == 0) continue;
    ++busy;
    EXPECT_LE(hb.progress, progress_after_steps);
  }
  EXPECT_GE(busy, 4) << "heartbeats sent during 800 ms of work at 20 Hz";
  const auto longest = std::max_element(beats.begin(), beats.end(), [](auto& a, auto& b) { return a.busy_ms < b.busy_ms; });
  ASSERT_NE(longest, beats.end());
  EXPECT_GE(longest->busy_ms, 300);
  for (size_t i = 1; i < beats.size(); ++i) EXPECT_EQ(beats[i].seq, beats[i - 1].seq + 1);
}

TEST(NodeOptions, LoadedAndValidated)
{
  const auto c = config::Config::parse("node:\n  name: x\n  heartbeat_hz: 10\n", "n.yaml");
  const auto o = load_node_options(c.section("node"), "default");
  EXPECT_EQ(o.name, "x");
  EXPECT_DOUBLE_EQ(o.heartbeat_hz, 10);
  EXPECT_EQ(o.realtime_priority, 0);   // normal scheduling unless asked
  const auto bad = config::Config::parse("node:\n  heartbeat_hz: 1000\n", "n.yaml");
  EXPECT_THROW(load_node_options(bad.section("node"), "d"), config::ConfigError);
  const auto rt = config::Config::parse("node:\n  realtime_priority: 43\n", "n.yaml");
  EXPECT_EQ(load_node_options(rt.section("node"), "d").realtime_priority, 43);
  const auto bad_rt = config::Config::parse("node:\n  realtime_priority: 100\n", "n.yaml");
  EXPECT_THROW(load_node_options(bad_rt.section("node"), "d"), config::ConfigError);
}

}  // namespace
}  // namespace rgnav::runtime
