// The fault harness's observer judges a process's heartbeat by when it was sent, not by when the
// observer got to read it: while the harness publishes a flood it reads its queue only between
// batches, and heartbeats sent on time reached it seconds late.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <vector>

#include "bus_observer.h"
#include "rgnav/heartbeat_t.hpp"
#include "time/message_time.h"

namespace rgnav::fault {
namespace {

void beat(BusObserver& obs, int64_t seq, int64_t sent_utime)
{
  heartbeat_t hb{};
  hb.utime = sent_utime;
  hb.name = "worker";
  hb.host = "here";
  hb.pid = 42;
  hb.seq = seq;
  std::vector<uint8_t> buf(static_cast<size_t>(hb.getEncodedSize()));
  hb.encode(buf.data(), 0, static_cast<int>(buf.size()));
  obs.bus().publish("HEARTBEAT", buf.data(), buf.size());
}

TEST(BusObserver, JudgesHeartbeatGapsByWhenTheyWereSent)
{
  BusObserver obs("memq://", "here", {}, {}, BusObserver::Channels{});
  beat(obs, 1, time::wall_utime());
  obs.spin(std::chrono::milliseconds(20));
  obs.reset_gaps();
  // The observer reads nothing for a second while the worker beats every 200 ms ...
  const int64_t t0 = time::wall_utime();
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  // ... then reads all six beats at once (the last sent just now).
  for (int k = 0; k < 6; ++k) beat(obs, 2 + k, t0 + 200'000 * k);
  obs.spin(std::chrono::milliseconds(20));
  const auto* t = obs.heartbeat("worker");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->lost, 0);
  EXPECT_LT(obs.gap_now("worker").count(), 400) << "the worker beat every 200 ms";
  EXPECT_GE(obs.max_late().count(), 700) << "the first of them waited about a second to be read";
  // Silence is silence: no beat for 600 ms more is a gap of at least that since the last one sent.
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  EXPECT_GE(obs.gap_now("worker").count(), 590);
}

}  // namespace
}  // namespace rgnav::fault
