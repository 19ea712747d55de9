#include "bus/typed.h"

#include <gtest/gtest.h>

#include <cmath>

#include "bus/fake_bus.h"
#include "bus/lcm_bus.h"
#include "laser_scan_msg.h"

namespace rgnav::bus {
namespace {

laser_scan_t make_scan(int64_t id)
{
  laser_scan_t s = testing::laser_scan_msg(1'000'000 + id, id, 8.183f, 2.5f);
  s.scan_time = 1.0f / 75;
  return s;
}

TEST(TypedBus, RoundTripOverFakeBus)
{
  FakeBus bus;
  DropCounter drops;
  std::vector<laser_scan_t> got;
  subscribe<laser_scan_t>(bus, "LASER_FRONT", [&](const laser_scan_t& m, const RawMessage&) { got.push_back(m); }, &drops);
  ASSERT_TRUE(publish(bus, "LASER_FRONT", make_scan(7)));
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].scan_id, 7);
  EXPECT_EQ(got[0].ranges, make_scan(7).ranges);
  EXPECT_EQ(drops.total(), 0);
}

TEST(TypedBus, PublishRefusesInconsistentCounts)
{
  FakeBus bus;
  auto s = make_scan(1);
  s.nranges = 500;  // would make LCM's encoder read past the vector
  EXPECT_FALSE(publish(bus, "LASER_FRONT", s));
  EXPECT_TRUE(bus.published().empty());
}

TEST(TypedBus, PublishRefusesNonFiniteAndInvalidValues)
{
  FakeBus bus;
  auto s = make_scan(1);
  s.ranges[3] = NAN;
  EXPECT_FALSE(publish(bus, "LASER_FRONT", s));
  s = make_scan(1);
  s.angle_increment = -0.1f;
  EXPECT_FALSE(publish(bus, "LASER_FRONT", s));
  EXPECT_TRUE(bus.published().empty());
}

TEST(TypedBus, WrongTypeOnChannelIsDroppedAndCounted)
{
  FakeBus bus;
  DropCounter drops;
  int delivered = 0;
  subscribe<odometry_t>(bus, "ODOMETRY", [&](const odometry_t&, const RawMessage&) { ++delivered; }, &drops);
  ASSERT_TRUE(publish(bus, "ODOMETRY", make_scan(1)));  // a scan where odometry is expected
  EXPECT_EQ(delivered, 0);
  EXPECT_EQ(drops.total(), 1);
  EXPECT_EQ(drops.on_channel("ODOMETRY"), 1);
}

TEST(TypedBus, RawGarbageIsDroppedAndCounted)
{
  FakeBus bus;
  DropCounter drops;
  int delivered = 0;
  subscribe<laser_scan_t>(bus, "LASER_FRONT", [&](const laser_scan_t&, const RawMessage&) { ++delivered; }, &drops);
  const uint8_t junk[] = {1, 2, 3};
  bus.publish("LASER_FRONT", junk, sizeof junk);
  bus.publish("LASER_FRONT", nullptr, 0);
  EXPECT_EQ(delivered, 0);
  EXPECT_EQ(drops.total(), 2);
}

TEST(TypedBus, SemanticCheckOnReceive)
{
  // A message that passes the wire checks but is meaningless (deadline 0) never reaches the handler.
  FakeBus bus;
  DropCounter drops;
  int delivered = 0;
  subscribe<velocity_cmd_t>(bus, "BASE_CMD", [&](const velocity_cmd_t&, const RawMessage&) { ++delivered; }, &drops);
  velocity_cmd_t c{};
  c.utime = 5;
  c.deadline_us = 0;
  c.source = "test";
  std::vector<uint8_t> buf(static_cast<size_t>(c.getEncodedSize()));
  c.encode(buf.data(), 0, static_cast<int>(buf.size()));  // bypasses publish()'s own check
  bus.publish("BASE_CMD", buf.data(), buf.size());
  EXPECT_EQ(delivered, 0);
  EXPECT_EQ(drops.total(), 1);
}

TEST(TypedBus, RoundTripOverMemq)
{
  LcmBus bus("memq://");
  DropCounter drops;
  std::vector<int64_t> ids;
  subscribe<laser_scan_t>(bus, "LASER_FRONT", [&](const laser_scan_t& m, const RawMessage&) { ids.push_back(m.scan_id); }, &drops);
  for (int64_t i = 1; i <= 5; ++i) ASSERT_TRUE(publish(bus, "LASER_FRONT", make_scan(i)));
  while (bus.handle(std::chrono::milliseconds(10)) > 0) {
  }
  EXPECT_EQ(ids, (std::vector<int64_t>{1, 2, 3, 4, 5}));
}

TEST(LcmBus, BadUrlThrows)
{
  EXPECT_THROW(LcmBus("nosuchprovider://x"), BusError);
}

}  // namespace
}  // namespace rgnav::bus
