// The supervisor's node over the synchronous FakeBus: an order on SUPERVISOR_ORDERS is carried
// out only when signed with the deputy's key; an unsigned one (or one signed with another key,
// or a replay) is refused, and the status's alert names the refused sender and the last one
// whose order was carried out.
#include "supervisor_node.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>

#include "fake_bus_node.h"
#include "launch_parser.h"
#include "order_conversions.h"
#include "rgnav/supervisor_status_t.hpp"
#include "sample_messages.h"
#include "time/message_time.h"

namespace rgnav::supervisor {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

OrderKey key_of(uint8_t fill) { return order_key_from_bytes(std::vector<uint8_t>(32, fill)); }

TEST(OrderConversions, EveryFieldSurvivesTheRoundTrip)
{
  for (uint32_t v = 0; v < 12; ++v) {
    const supervisor_order_t m = rgnav::testing::sample<supervisor_order_t>(v);
    const OrderFields o = to_order_fields(m);
    EXPECT_EQ(o.mac, m.mac);
    EXPECT_EQ(o.nonce, m.nonce);
    const supervisor_order_t back = to_order_msg(o);
    std::vector<uint8_t> a(m.getEncodedSize()), b(back.getEncodedSize());
    m.encode(a.data(), 0, static_cast<int>(a.size()));
    back.encode(b.data(), 0, static_cast<int>(b.size()));
    EXPECT_EQ(a, b) << "variant " << v;
  }
}

class SupervisorNodeOrders : public ::testing::Test
{
 protected:
  void SetUp() override
  {
    dir_ = std::filesystem::temp_directory_path() / ("rgnav_sup_node_test_" + std::to_string(getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    SupervisorOptions options;
    options.tick = 10ms;
    options.status_min_gap = 0ms;
    // One command the launch leaves stopped (start_all is not called): only an order starts it.
    auto plan = make_plan(parse_launch_text("cmd \"sleeper\" { exec = \"sleep 30\"; heartbeat = \"false\"; stop_signal = 15; }\n", "t.pmd"),
                          {"/tmp", "", false});
    auto sup = std::make_unique<Supervisor>(std::move(plan), "testhost", options, dir_.string());
    runtime::NodeOptions no;
    no.name = "supervisor";
    no.input_stale_after = 0ms;
    // Not HEARTBEAT, which the supervisor listens to: the FakeBus delivers a publish at once,
    // and Node::send_heartbeat publishes under the lock its own input handling takes.
    no.heartbeat_channel = "TEST_SUPERVISOR_HEARTBEAT";
    n_ = std::make_unique<rgnav::testing::FakeBusNode>(no);
    node_ = std::make_unique<SupervisorNode>(*n_->node, std::move(sup), options, SupervisorChannels{},
                                             OrderGate(OrderVerifier(key_, "test key", 10000ms)));
  }

  void TearDown() override
  {
    node_.reset();  // stops the children
    n_.reset();
    std::filesystem::remove_all(dir_);
  }

  void send(OrderFields o) { bus::publish(*n_->bus, "SUPERVISOR_ORDERS", to_order_msg(o)); }

  OrderFields order(int8_t what, int64_t id)
  {
    OrderFields o;
    o.utime = time::wall_utime();
    o.order_id = id;
    o.host = "testhost";
    o.order = what;
    o.target = "sleeper";
    o.source = "rgnav_ctl@laptop:42";
    return o;
  }

  supervisor_status_t status()
  {
    node_->publish_status();
    return rgnav::testing::decoded<supervisor_status_t>(*n_->bus, "SUPERVISOR_STATUS").back();
  }

  std::string state_of_sleeper()
  {
    const auto s = status();
    for (const auto& p : s.processes)
      if (p.name == "sleeper") return std::to_string(p.state);
    return "?";
  }

  // Spins the node's loop (timers: tick, status) for a while.
  void spin_for(std::chrono::milliseconds d)
  {
    const auto until = Clock::now() + d;
    while (Clock::now() < until) n_->node->spin_once(5ms);
  }
  bool spin_until(const std::function<bool()>& pred, std::chrono::milliseconds limit)
  {
    const auto until = Clock::now() + limit;
    while (Clock::now() < until) {
      if (pred()) return true;
      n_->node->spin_once(5ms);
    }
    return pred();
  }

  const std::string kStopped = std::to_string(process_status_t::STATE_STOPPED);
  const std::string kRunning = std::to_string(process_status_t::STATE_RUNNING);
  OrderKey key_ = key_of(7);
  std::filesystem::path dir_;
  std::unique_ptr<rgnav::testing::FakeBusNode> n_;
  std::unique_ptr<SupervisorNode> node_;
};

TEST_F(SupervisorNodeOrders, AnUnsignedOrderIsRefusedAndAlertedASignedOneIsCarriedOut)
{
  ASSERT_EQ(state_of_sleeper(), kStopped);

  // Unsigned: nothing starts; the alert names the sender.
  OrderFields unsigned_start = order(supervisor_order_t::ORDER_START, 1);
  unsigned_start.source = "intruder@robot-net:666";
  send(unsigned_start);
  spin_for(300ms);
  EXPECT_EQ(state_of_sleeper(), kStopped);
  auto s = status();
  EXPECT_NE(s.alert.find("intruder@robot-net:666"), std::string::npos) << s.alert;
  EXPECT_NE(s.alert.find("unsigned"), std::string::npos) << s.alert;

  // Signed with another key: refused as well.
  OrderFields other = order(supervisor_order_t::ORDER_START, 2);
  sign_order(other, key_of(8));
  send(other);
  spin_for(300ms);
  EXPECT_EQ(state_of_sleeper(), kStopped);

  // Signed with the deputy's key: started.
  OrderFields good = order(supervisor_order_t::ORDER_START, 3);
  sign_order(good, key_);
  send(good);
  ASSERT_TRUE(spin_until([&] { return state_of_sleeper() == kRunning; }, 5000ms)) << state_of_sleeper();

  // The same signed copy played back (e.g. after the operator stopped it): refused; the alert
  // now names the last sender whose order was carried out too.
  OrderFields stop = order(supervisor_order_t::ORDER_STOP, 4);
  sign_order(stop, key_);
  send(stop);
  ASSERT_TRUE(spin_until([&] { return state_of_sleeper() == kStopped; }, 5000ms)) << state_of_sleeper();
  OrderFields replay = good;
  replay.source = good.source;
  send(replay);
  spin_for(300ms);
  EXPECT_EQ(state_of_sleeper(), kStopped) << "a replayed start was carried out";
}

TEST_F(SupervisorNodeOrders, TheAlertOfARefusalNamesBothSources)
{
  OrderFields good = order(supervisor_order_t::ORDER_START, 1);
  sign_order(good, key_);
  send(good);
  ASSERT_TRUE(spin_until([&] { return state_of_sleeper() == kRunning; }, 5000ms));
  OrderFields forged = order(supervisor_order_t::ORDER_STOP, 2);
  forged.source = "intruder@robot-net:666";
  sign_order(forged, key_of(9));
  send(forged);
  spin_for(200ms);
  EXPECT_EQ(state_of_sleeper(), kRunning);
  const auto s = status();
  EXPECT_NE(s.alert.find("intruder@robot-net:666"), std::string::npos) << s.alert;
  EXPECT_NE(s.alert.find("rgnav_ctl@laptop:42"), std::string::npos) << s.alert;
}

}  // namespace
}  // namespace rgnav::supervisor
