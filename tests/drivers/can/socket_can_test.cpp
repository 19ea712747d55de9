// SocketCAN: real kernel code, tested where the kernel has CAN (vcan0 for the round trip);
// skipped with the reason elsewhere.
#include <gtest/gtest.h>

#include "bus/can_frames.h"
#include "bus/socket_can.h"

namespace rgnav::can {
namespace {

using namespace std::chrono_literals;

TEST(SocketCan, OpensOrExplainsWhyNot)
{
  std::string why;
  if (!SocketCan::kernel_supports_can(&why)) {
    // The constructor must fail the same way, with a message naming the interface.
    try {
      SocketCan s("vcan0");
      FAIL() << "SocketCan opened although socket(PF_CAN) fails";
    } catch (const CanError& e) {
      EXPECT_NE(std::string(e.what()).find("vcan0"), std::string::npos) << e.what();
    }
    GTEST_SKIP() << "kernel has no CAN support: " << why;
  }
  EXPECT_THROW(SocketCan("rgnav-no-such-if"), CanError);
}

TEST(SocketCan, RoundTripOnVcan0)
{
  std::string why;
  if (!SocketCan::kernel_supports_can(&why)) GTEST_SKIP() << "kernel has no CAN support: " << why;
  std::unique_ptr<SocketCan> a, b;
  try {
    a = std::make_unique<SocketCan>("vcan0");
    b = std::make_unique<SocketCan>("vcan0");
  } catch (const CanError& e) {
    GTEST_SKIP() << "no vcan0 (ip link add dev vcan0 type vcan; ip link set vcan0 up): " << e.what();
  }
  b->set_filters({{0x181, CAN_SFF_MASK}});
  a->send(make_frame(0x701, {5}), 100ms);
  ASSERT_TRUE(a->send(make_frame(0x181, {1, 2, 3}), 100ms));
  auto f = b->receive(1000ms);
  ASSERT_TRUE(f);
  EXPECT_EQ(frame_id(*f), 0x181u);
  EXPECT_EQ(f->can_dlc, 3);
  EXPECT_FALSE(b->bus_off());
}

}  // namespace
}  // namespace rgnav::can
