#include "lld/lld_node.h"

#include <gtest/gtest.h>

#include "fake_bus_node.h"
#include "msg/conversions.h"
#include "trajectory/trajectory_conversions.h"

namespace rgnav::lld {
namespace {

TEST(LldNode, TracksOverFakeBus)
{
  rgnav::testing::FakeBusNode n("lld");
  bus::FakeBus* fake = n.bus;
  runtime::Node& node = *n.node;
  LldOptions options;
  LldNode lld(node, options, /*start_thread=*/false);

  const int64_t t0 = 1'700'000'000'000'000;
  odometry_t odo{};
  odo.utime = t0;
  odo.seq = 1;
  odo.status = odometry_t::STATUS_OK;
  ASSERT_TRUE(bus::publish(*fake, "ODOMETRY", odo));

  trajectory::Trajectory t;
  t.id = 7;
  t.stamp = time::from_utime(t0);
  t.chain.push_back(trajectory::Segment::line(geometry::Pose2(), 2.0));
  ASSERT_TRUE(bus::publish(*fake, "TRAJECTORY", trajectory::to_msg(t, nullptr, 0.5)));
  fake->clear();

  lld.control_step(time::from_utime(t0 + 50'000), 0.05, 0.1);
  const auto cmds = fake->published_on("BASE_CMD");
  const auto stats = fake->published_on("LLD_STATUS");
  ASSERT_EQ(cmds.size(), 1u);
  ASSERT_EQ(stats.size(), 1u);
  velocity_cmd_t cmd;
  std::string why;
  ASSERT_TRUE(bus::decode(cmds[0].data.data(), cmds[0].data.size(), &cmd, &why)) << why;
  EXPECT_GT(cmd.v, 0.0);
  EXPECT_LE(cmd.v, options.follower.limits.a_max * 0.05 + 1e-9);
  EXPECT_EQ(cmd.deadline_us, options.loop.command_deadline_ms * 1000);
  EXPECT_EQ(cmd.source, "lld");
  lld_status_t st;
  ASSERT_TRUE(bus::decode(stats[0].data.data(), stats[0].data.size(), &st, &why)) << why;
  EXPECT_EQ(st.trajectory_id, 7);
  EXPECT_EQ(st.state, lld_status_t::STATE_TRACKING);
  EXPECT_FLOAT_EQ(st.period_jitter_ms, 0.1f);

  // Odometry stops coming: after the timeout the drive brakes to a standstill.
  for (int i = 2; i < 80; ++i) lld.control_step(time::from_utime(t0 + i * 50'000), 0.05, 0.0);
  const auto last = fake->published_on("LLD_STATUS").back();
  ASSERT_TRUE(bus::decode(last.data.data(), last.data.size(), &st, &why));
  EXPECT_EQ(st.v_cmd, 0.0);
  EXPECT_NE(st.state, lld_status_t::STATE_TRACKING);
}

TEST(LldNode, RejectsBadTrajectory)
{
  rgnav::testing::FakeBusNode n("lld");
  bus::FakeBus* fake = n.bus;
  runtime::Node& node = *n.node;
  LldNode lld(node, LldOptions{}, false);
  trajectory_t m{};
  m.utime = 1;
  m.trajectory_id = 3;
  m.frame = trajectory_t::FRAME_ODOM;
  m.nsegments = 1;
  m.segments.resize(1);
  m.segments[0].kind = 99;  // passes the wire check only if the enum is unchecked
  m.segments[0].v_max = 0.5;
  m.a_max = 0.5;
  m.omega_max = 1.0;
  std::vector<uint8_t> raw(static_cast<size_t>(m.getEncodedSize()));
  m.encode(raw.data(), 0, static_cast<int>(raw.size()));  // unchecked: a broken sender
  fake->publish("TRAJECTORY", raw.data(), raw.size());
  lld.control_step(time::from_utime(100'000), 0.05, 0.0);
  EXPECT_EQ(lld.follower().status().state, FollowerState::kIdle);
  EXPECT_EQ(node.drops().total(), 1);  // refused by the wire check or by from_msg: counted either way
}

// One input stamped far ahead (a corrupted copy) is dropped and counted, not taken as the
// robot's time: taken, it would make the odometry look stale and stop the robot for as long as
// the stamp is ahead. A second input stamped near it confirms a real jump.
TEST(LldNode, OneInputStampedFarAheadIsDroppedUntilAnotherConfirmsIt)
{
  rgnav::testing::FakeBusNode n("lld");
  bus::FakeBus* fake = n.bus;
  LldNode lld(*n.node, LldOptions{}, false);
  const int64_t t0 = 1'700'000'000'000'000;
  odometry_t odo{};
  odo.status = odometry_t::STATUS_OK;
  auto send = [&](int64_t utime) {
    odo.utime = utime;
    ++odo.seq;
    ASSERT_TRUE(bus::publish(*fake, "ODOMETRY", odo));
  };
  send(t0);
  send(t0 + 20'000);
  EXPECT_EQ(n.node->drops().total(), 0);
  send(t0 + 600'000'000);  // ten minutes ahead
  EXPECT_EQ(n.node->drops().total(), 1);
  EXPECT_LT(time::to_utime(lld.message_now()), t0 + 60'000'000);  // wall time since: seconds at most
  send(t0 + 40'000);  // the stream goes on: taken
  EXPECT_EQ(n.node->drops().total(), 1);
  send(t0 + 600'000'000);
  send(t0 + 600'020'000);  // two near each other: the robot's time did jump
  EXPECT_EQ(n.node->drops().total(), 2);
  EXPECT_GE(time::to_utime(lld.message_now()), t0 + 600'020'000);
}

// The process stopped while driving (SIGSTOP) and continued (the supervisor's SIGCONT before its
// SIGTERM): the base driver's deadman stopped the robot meanwhile. On waking, the node's thread
// may take in odometry queued during the gap before the control loop's first cycle, so the
// odometry looks fresh while the reference ran on by the whole gap: tracking it would command
// the robot off again. The first cycle after the gap must command zero, and a trajectory queued
// during the gap must not be taken up; one planned after it is.
TEST(LldNode, TheFirstCycleAfterTheLoopWasHeldUpCommandsZero)
{
  rgnav::testing::FakeBusNode n("lld");
  bus::FakeBus* fake = n.bus;
  LldOptions options;
  LldNode lld(*n.node, options, /*start_thread=*/false);
  const int64_t t0 = 1'700'000'000'000'000;
  const int64_t period = 50'000;
  double x = 0.0, v = 0.0;  // the robot: follows the command
  odometry_t odo{};
  odo.status = odometry_t::STATUS_OK;
  auto send_odometry = [&](int64_t utime) {
    odo.utime = utime;
    ++odo.seq;
    odo.odom_from_base.x = x;
    odo.v = v;
    ASSERT_TRUE(bus::publish(*fake, "ODOMETRY", odo));
  };
  auto send_trajectory = [&](int64_t id, int64_t stamp) {
    trajectory::Trajectory t;
    t.id = id;
    t.stamp = time::from_utime(stamp);
    t.chain.push_back(trajectory::Segment::line(geometry::Pose2(x, 0.0, 0.0), 6.0));
    ASSERT_TRUE(bus::publish(*fake, "TRAJECTORY", trajectory::to_msg(t, nullptr, 0.5)));
  };
  auto last_command = [&] {
    const auto cmds = fake->published_on("BASE_CMD");
    velocity_cmd_t cmd{};
    std::string why;
    if (!cmds.empty()) {
      EXPECT_TRUE(bus::decode(cmds.back().data.data(), cmds.back().data.size(), &cmd, &why)) << why;
    }
    return cmd;
  };
  send_odometry(t0);
  send_trajectory(7, t0);
  int64_t now = t0;
  for (int i = 0; i < 40; ++i) {  // 2 s: up to cruise speed, the trajectory re-sent at 2 Hz
    now += period;
    if (i % 10 == 9) send_trajectory(7, now - period);
    lld.control_step(time::from_utime(now), 0.05, 0.0);
    v = last_command().v;
    x += v * 0.05;
    send_odometry(now);
  }
  ASSERT_GT(last_command().v, 0.2);
  ASSERT_EQ(lld.follower().status().state, FollowerState::kTracking);

  // Stopped for 0.6 s; the deadman stopped the robot ~0.1 m on. The queued odometry and a
  // trajectory planned during the gap are taken in before the loop's first cycle.
  const int64_t gap = 600'000;
  x += 0.1;
  v = 0.0;
  for (int64_t t = now + 20'000; t <= now + gap; t += 20'000) send_odometry(t);
  send_trajectory(8, now + gap / 2);
  fake->clear();
  now += gap;
  lld.control_step(time::from_utime(now + 5'000), 1e-6 * static_cast<double>(gap), 0.0);
  ASSERT_EQ(fake->published_on("BASE_CMD").size(), 1u);
  EXPECT_EQ(last_command().v, 0.0);
  EXPECT_EQ(last_command().omega, 0.0);
  EXPECT_EQ(lld.follower().status().state, FollowerState::kIdle);

  // The loop runs on: the trajectory queued during the gap is not followed.
  for (int i = 0; i < 5; ++i) {
    now += period;
    send_odometry(now);
    lld.control_step(time::from_utime(now), 0.05, 0.0);
    EXPECT_EQ(last_command().v, 0.0);
  }
  EXPECT_EQ(lld.follower().status().state, FollowerState::kIdle);

  // A trajectory planned after the gap is.
  send_trajectory(9, now);
  for (int i = 0; i < 5; ++i) {
    now += period;
    send_odometry(now);
    lld.control_step(time::from_utime(now), 0.05, 0.0);
  }
  EXPECT_EQ(lld.follower().status().state, FollowerState::kTracking);
  EXPECT_GT(last_command().v, 0.0);
}

TEST(PeriodicLoop, TicksAndStops)
{
  PeriodicLoop loop(std::chrono::milliseconds(5));
  PeriodicLoop::Tick tick;
  int n = 0;
  while (n < 10 && loop.wait(&tick)) ++n;
  EXPECT_EQ(n, 10);
  EXPECT_EQ(loop.stats().ticks, 10);
  loop.stop();
  EXPECT_FALSE(loop.wait(&tick));
}

}  // namespace
}  // namespace rgnav::lld
