// The user-space virtual CAN bus: forwarding between clients (threads and, via the process
// test, processes), filters and error masks with kernel semantics, and the test hooks.
#include <gtest/gtest.h>
#include <unistd.h>

#include <thread>

#include "bus/can_frames.h"
#include "bus/vcan_broker.h"
#include "bus/virtual_can.h"

namespace rgnav::can {
namespace {

using namespace std::chrono_literals;

std::string unique_path(const std::string& tag)
{
  return "/tmp/rgnav-vcan-test-" + tag + "-" + std::to_string(::getpid()) + ".sock";
}

VirtualCanOptions client(const std::string& path, const std::string& name)
{
  VirtualCanOptions o;
  o.path = path;
  o.client_name = name;
  o.connect_timeout = 2000ms;
  return o;
}

// Waits until the broker has seen `n` clients with names (HELLO processed).
void wait_clients(const VcanBroker& b, size_t n)
{
  for (int i = 0; i < 200 && b.client_names().size() < n; ++i) std::this_thread::sleep_for(5ms);
  for (int i = 0; i < 200; ++i) {
    size_t named = 0;
    for (const auto& c : b.client_names()) named += c.rfind("client-", 0) != 0;
    if (named >= n) return;
    std::this_thread::sleep_for(5ms);
  }
}

TEST(CanFrames, FilterSemanticsMatchCanRaw)
{
  const can_frame f = make_frame(0x181, {1, 2});
  EXPECT_TRUE(passes_filters(f, {{0x181, CAN_SFF_MASK}}));
  EXPECT_FALSE(passes_filters(f, {{0x182, CAN_SFF_MASK}}));
  EXPECT_TRUE(passes_filters(f, {{0x180, 0x780}}));                    // function code match
  EXPECT_FALSE(passes_filters(f, {{0x181 | CAN_INV_FILTER, CAN_SFF_MASK}}));  // inverted
  EXPECT_TRUE(passes_filters(f, {{0x100 | CAN_INV_FILTER, CAN_SFF_MASK}}));
  EXPECT_FALSE(passes_filters(f, {}));
  EXPECT_EQ(to_string(f), "181#0102");
  const can_frame e = make_error_frame(CAN_ERR_BUSOFF);
  EXPECT_TRUE(is_error_frame(e));
  EXPECT_TRUE(classify_error(e).bus_off);
  EXPECT_TRUE(passes_error_mask(e, CAN_ERR_BUSOFF));
  EXPECT_FALSE(passes_error_mask(e, CAN_ERR_ACK));
}

TEST(VirtualCanBus, ForwardsEveryFrameToAllOtherClients)
{
  VcanBroker broker(unique_path("fwd"));
  broker.start();
  VirtualCan a(client(broker.path(), "a")), b(client(broker.path(), "b")), c(client(broker.path(), "c"));
  wait_clients(broker, 3);
  for (uint8_t i = 0; i < 50; ++i) ASSERT_TRUE(a.send(make_frame(0x200 + i, {i, 0xAA}), 100ms));
  for (auto* rx : {&b, &c}) {
    for (uint8_t i = 0; i < 50; ++i) {
      auto f = rx->receive(1000ms);
      ASSERT_TRUE(f) << "frame " << int(i) << " missing";
      EXPECT_EQ(frame_id(*f), 0x200u + i);  // in order
      EXPECT_EQ(f->data[0], i);
      EXPECT_EQ(f->can_dlc, 2);
    }
  }
  // The sender does not receive its own frames (SocketCAN default without RECV_OWN_MSGS).
  EXPECT_FALSE(a.receive(50ms));
  EXPECT_EQ(broker.stats().frames_in, 50u);
  EXPECT_EQ(broker.stats().deliveries, 100u);
}

TEST(VirtualCanBus, AbstractNamespaceAndFilters)
{
  VcanBroker broker("@rgnav-vcan-test-" + std::to_string(::getpid()));
  broker.start();
  VirtualCan tx(client(broker.path(), "tx")), rx(client(broker.path(), "rx"));
  rx.set_filters({{0x180, 0x780}});  // TPDO1 of any node only
  wait_clients(broker, 2);
  tx.send(make_frame(0x701, {5}), 100ms);
  tx.send(make_frame(0x182, {7}), 100ms);
  auto f = rx.receive(1000ms);
  ASSERT_TRUE(f);
  EXPECT_EQ(frame_id(*f), 0x182u);
  EXPECT_FALSE(rx.receive(50ms));
}

TEST(VirtualCanBus, RefusesSecondBrokerAndMissingBroker)
{
  const std::string path = unique_path("dup");
  VcanBroker broker(path);
  EXPECT_THROW(VcanBroker second(path), CanError);
  VirtualCanOptions o;
  o.path = unique_path("nobody");
  o.connect_timeout = 50ms;
  EXPECT_THROW(VirtualCan nobody(o), CanError);
}

TEST(VirtualCanBus, DropHookRemovesMatchingFrames)
{
  VcanBroker broker(unique_path("drop"));
  broker.start();
  VirtualCan a(client(broker.path(), "a")), b(client(broker.path(), "b"));
  wait_clients(broker, 2);
  broker.drop_frames(0x181, CAN_SFF_MASK, 2);
  for (int i = 0; i < 3; ++i) a.send(make_frame(0x181, {static_cast<uint8_t>(i)}), 100ms);
  a.send(make_frame(0x281, {9}), 100ms);
  auto f1 = b.receive(1000ms);
  auto f2 = b.receive(1000ms);
  ASSERT_TRUE(f1 && f2);
  EXPECT_EQ(f1->data[0], 2);  // the first two 0x181 frames were dropped
  EXPECT_EQ(frame_id(*f2), 0x281u);
  EXPECT_EQ(broker.stats().dropped_by_hook, 2u);
  // The same hook through a control packet from a client.
  ASSERT_TRUE(a.request_drop_frames(0x300, 0x700, -1));
  std::this_thread::sleep_for(50ms);
  a.send(make_frame(0x305, {1}), 100ms);
  a.send(make_frame(0x405, {1}), 100ms);
  auto g = b.receive(1000ms);
  ASSERT_TRUE(g);
  EXPECT_EQ(frame_id(*g), 0x405u);
}

TEST(VirtualCanBus, ErrorFramesFollowTheErrorMask)
{
  VcanBroker broker(unique_path("err"));
  broker.start();
  VirtualCan a(client(broker.path(), "a")), b(client(broker.path(), "b"));
  a.set_error_mask(CAN_ERR_CRTL);
  wait_clients(broker, 2);
  broker.inject_error(CAN_ERR_CRTL, CAN_ERR_CRTL_TX_PASSIVE);
  auto e = a.receive(1000ms);
  ASSERT_TRUE(e);
  EXPECT_TRUE(is_error_frame(*e));
  EXPECT_TRUE(classify_error(*e).error_passive);
  EXPECT_FALSE(b.receive(100ms)) << "b did not ask for error frames";
  // Clients cannot put error frames on the bus.
  EXPECT_FALSE(a.send(make_error_frame(CAN_ERR_BUSOFF), 10ms));
}

TEST(VirtualCanBus, BusOffIsolatesOneClientThenRestarts)
{
  VcanBroker broker(unique_path("busoff"));
  broker.start();
  VirtualCan a(client(broker.path(), "a")), b(client(broker.path(), "b"));
  a.set_error_mask(CAN_ERR_BUSOFF | CAN_ERR_RESTARTED);
  wait_clients(broker, 2);
  ASSERT_TRUE(broker.bus_off("a", 150ms));
  auto e = a.receive(1000ms);
  ASSERT_TRUE(e);
  EXPECT_TRUE(classify_error(*e).bus_off);
  EXPECT_TRUE(a.bus_off());
  EXPECT_FALSE(a.send(make_frame(0x100, {}), 10ms)) << "a bus-off controller does not transmit";
  b.send(make_frame(0x101, {}), 100ms);  // not delivered to a while bus-off
  auto r = a.receive(1000ms);
  ASSERT_TRUE(r);
  EXPECT_TRUE(classify_error(*r).restarted) << to_string(*r);
  EXPECT_FALSE(a.bus_off());
  ASSERT_TRUE(a.send(make_frame(0x102, {}), 100ms));
  auto g = b.receive(1000ms);
  ASSERT_TRUE(g);
  EXPECT_EQ(frame_id(*g), 0x102u);
  EXPECT_FALSE(broker.bus_off("nobody", 10ms));
}

TEST(VirtualCanBus, DisconnectLooksLikeBusOffAndReconnects)
{
  VcanBroker broker(unique_path("disc"));
  broker.start();
  auto o = client(broker.path(), "victim");
  o.reconnect_interval = 50ms;
  VirtualCan victim(o), other(client(broker.path(), "other"));
  victim.set_error_mask(CAN_ERR_BUSOFF | CAN_ERR_RESTARTED);
  wait_clients(broker, 2);
  ASSERT_TRUE(other.request_disconnect("victim"));
  auto e = victim.receive(1000ms);
  ASSERT_TRUE(e);
  EXPECT_TRUE(classify_error(*e).bus_off);
  auto r = victim.receive(2000ms);
  ASSERT_TRUE(r) << "no reconnect";
  EXPECT_TRUE(classify_error(*r).restarted);
  EXPECT_TRUE(victim.connected());
  wait_clients(broker, 2);
  other.send(make_frame(0x123, {1}), 100ms);
  auto f = victim.receive(1000ms);
  ASSERT_TRUE(f);
  EXPECT_EQ(frame_id(*f), 0x123u);
}

TEST(VirtualCanBus, BrokerGoneMeansBusOffForClients)
{
  auto broker = std::make_unique<VcanBroker>(unique_path("gone"));
  broker->start();
  VirtualCan a(client(broker->path(), "a"));
  a.set_error_mask(CAN_ERR_BUSOFF);
  wait_clients(*broker, 1);
  broker.reset();
  auto e = a.receive(1000ms);
  ASSERT_TRUE(e);
  EXPECT_TRUE(classify_error(*e).bus_off);
  EXPECT_FALSE(a.connected());
  EXPECT_FALSE(a.send(make_frame(0x1, {}), 10ms));
}

}  // namespace
}  // namespace rgnav::can
