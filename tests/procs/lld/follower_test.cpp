#include "lld/follower.h"
#include "lld/stall_credit.h"

#include <gtest/gtest.h>

#include <cmath>

#include "trajectory/construct.h"
#include "unicycle_plant.h"

namespace rgnav::lld {
namespace {

using trajectory::Chain;
using trajectory::Segment;

constexpr double kDt = 0.05;  // 20 Hz

FollowerOptions options()
{
  FollowerOptions o;
  o.limits.v_max = 0.7;  // profiles at 85 %: ~0.6 m/s
  o.limits.a_max = 0.5;
  o.limits.a_lat_max = 0.5;
  o.limits.omega_max = 1.2;
  o.limits.alpha_max = 2.0;
  o.feedforward_lead = 0.1;  // the plant's lag
  return o;
}

trajectory::Trajectory make_trajectory(Chain chain, int64_t id)
{
  trajectory::Trajectory t;
  t.id = id;
  t.chain = std::move(chain);
  t.a_max = 0.5;
  t.omega_max = 1.2;
  return t;
}

struct FollowRun
{
  double max_xtrack_last_half = 0.0;
  double max_xtrack = 0.0;
  double end_error = 0.0;
  double time = 0.0;
  double predicted = 0.0;
  double max_dv = 0.0, max_dw = 0.0;
  bool done = false;
};

// Follows `chain` from the robot pose `start` with the lagged unicycle.
FollowRun follow(const Chain& chain, const geometry::Pose2& start, double v_max = 0.6)
{
  FollowerOptions o = options();
  o.limits.v_max = v_max;
  Follower f(o);
  testing::UnicyclePlant plant;
  plant.pose = start;
  time::Time now = time::from_utime(1'000'000'000);
  f.replace(make_plan(make_trajectory(chain, 1), o, 0.0), now);
  FollowRun r;
  r.predicted = f.plan()->profile.total_time();
  VelocityCommand prev;
  for (int i = 0; i < 2000; ++i) {
    OdometryInput odo{plant.pose, plant.v, plant.omega, now};
    const FollowerStatus& st = f.step(now, kDt, &odo);
    f.refresh(1, now);
    r.max_dv = std::max(r.max_dv, std::fabs(st.command.v - prev.v));
    r.max_dw = std::max(r.max_dw, std::fabs(st.command.omega - prev.omega));
    prev = st.command;
    if (st.state == FollowerState::kTracking) {
      r.max_xtrack = std::max(r.max_xtrack, std::fabs(st.cross_track));
      if (st.progress > 0.5 * chain.length())
        r.max_xtrack_last_half = std::max(r.max_xtrack_last_half, std::fabs(st.cross_track));
    }
    if (st.state == FollowerState::kDone) {
      r.done = true;
      r.time = i * kDt;
      break;
    }
    plant.advance(st.command, kDt);
    now += time::Duration(50'000);
  }
  r.end_error = (plant.pose.translation() - chain.end().translation()).norm();
  return r;
}

// A follower driving the lagged unicycle from the origin along a straight trajectory (id 1).
struct LineDrive
{
  explicit LineDrive(double length)
  {
    f.replace(make_plan(make_trajectory(Chain({Segment::line({}, length)}), 1), o, 0.0), now);
  }
  OdometryInput odometry() const { return {plant.pose, plant.v, plant.omega, now}; }
  // One 20 Hz period with the trajectory never refreshed: the follower steps on the plant's
  // odometry, the plant follows the command (if `plant_moves`), the clock advances.
  void unrefreshed_period(bool plant_moves = true)
  {
    const OdometryInput odo = odometry();
    f.step(now, kDt, &odo);
    if (plant_moves) plant.advance(f.last_command(), kDt);
    tick();
  }
  void tick() { now += time::Duration(50'000); }

  FollowerOptions o = options();
  Follower f{o};
  testing::UnicyclePlant plant;
  time::Time now = time::from_utime(1'000'000'000);
};

TEST(Follower, ConvergesOnLineFromOffset)
{
  const Chain line({Segment::line(geometry::Pose2(0, 0, 0), 4.0)});
  const FollowRun r = follow(line, geometry::Pose2(0.0, 0.15, -0.2));
  EXPECT_TRUE(r.done);
  EXPECT_GT(r.max_xtrack, 0.1);             // it did start off the path
  EXPECT_LT(r.max_xtrack_last_half, 0.01);  // and converged
  EXPECT_LT(r.end_error, 0.05);
}

TEST(Follower, ConvergesOnArcAndClothoid)
{
  Chain c;
  c.push_back(Segment::clothoid(geometry::Pose2(0, 0, 0), 0.0, 1.0, 1.0));
  c.append_at_end(Segment::arc({}, 1.0, 1.5));
  c.append_at_end(Segment::clothoid({}, 1.0, 0.0, 1.0));
  c.append_at_end(Segment::line({}, 1.5));
  const FollowRun r = follow(c, geometry::Pose2(-0.05, -0.1, 0.15));
  EXPECT_TRUE(r.done);
  EXPECT_LT(r.max_xtrack_last_half, 0.02);
  EXPECT_LT(r.end_error, 0.05);
  // Traversal time as predicted by the profile (the lag adds a little at the start).
  EXPECT_NEAR(r.time, r.predicted, 0.05 * r.predicted + 0.3);
}

TEST(Follower, LyapunovFunctionDecreasesWithoutLag)
{
  // Ideal unicycle (no lag, no saturation): V must not increase along the closed loop.
  FollowerOptions o = options();
  const Chain line({Segment::line(geometry::Pose2(0, 0, 0), 6.0)});
  // Reference moving at constant v_r = 0.3 on the line, robot starting off it.
  geometry::Pose2 robot(0.0, 0.2, 0.3);
  double prev_v = INFINITY;
  for (int i = 0; i < 400; ++i) {
    const double t = i * 0.005;
    const geometry::Pose2 ref(0.3 * t + 0.1, 0.0, 0.0);
    const TrackingError e = tracking_error(ref, robot);
    const double V = lyapunov(e, o.gains);
    EXPECT_LE(V, prev_v + 1e-9) << i;
    prev_v = V;
    const VelocityCommand u = kanayama(e, 0.3, 0.0, o.gains);
    robot = robot * geometry::Pose2(u.v * 0.005, 0, u.omega * 0.005);
  }
  EXPECT_LT(prev_v, 0.01);
}

TEST(Follower, TurnInPlaceThenDrive)
{
  Chain c;
  c.push_back(Segment::turn(geometry::Pose2(0, 0, 0), M_PI / 2));
  c.append_at_end(Segment::line({}, 1.0));
  const FollowRun r = follow(c, geometry::Pose2(0, 0, 0));
  EXPECT_TRUE(r.done);
  EXPECT_LT(r.end_error, 0.05);
}

TEST(Follower, ReplacementWithoutVelocityJump)
{
  LineDrive d(5.0);
  VelocityCommand prev;
  double max_dv = 0, max_dw = 0, v_at_switch = 0;
  for (int i = 0; i < 200; ++i) {
    if (i == 60) {
      // A new chain, veering left from where the robot is, at its current speed.
      v_at_switch = d.f.last_command().v;
      Chain c;
      c.push_back(Segment::arc(d.plant.pose, 0.8, 1.0));
      c.append_at_end(Segment::line({}, 1.0));
      d.f.replace(make_plan(make_trajectory(c, 2), d.o, d.f.last_command().v), d.now);
    }
    const OdometryInput odo = d.odometry();
    const FollowerStatus& st = d.f.step(d.now, kDt, &odo);
    d.f.refresh(st.trajectory_id, d.now);
    max_dv = std::max(max_dv, std::fabs(st.command.v - prev.v));
    max_dw = std::max(max_dw, std::fabs(st.command.omega - prev.omega));
    prev = st.command;
    d.plant.advance(st.command, kDt);
    d.tick();
  }
  EXPECT_GT(v_at_switch, 0.3);  // replaced while driving
  EXPECT_EQ(d.f.status().trajectory_id, 2);
  EXPECT_LE(max_dv, d.o.limits.a_max * kDt + 1e-9);
  EXPECT_LE(max_dw, d.o.limits.alpha_max * kDt + 1e-9);
}

TEST(Follower, StaleOdometryStopsWithinLimits)
{
  LineDrive d(8.0);
  const FollowerOptions& o = d.o;
  Follower& f = d.f;
  OdometryInput odo;
  for (int i = 0; i < 60; ++i) {
    odo = d.odometry();
    f.step(d.now, kDt, &odo);
    f.refresh(1, d.now);
    d.plant.advance(f.last_command(), kDt);
    d.tick();
  }
  const double v0 = f.last_command().v;
  ASSERT_GT(v0, 0.3);
  // Odometry freezes at `odo`.
  int steps = 0;
  double prev = v0;
  while (f.last_command().v > 0 && steps < 100) {
    f.step(d.now, kDt, &odo);
    f.refresh(1, d.now);
    EXPECT_LE(prev - f.last_command().v, o.stop_decel * kDt + 1e-9);
    prev = f.last_command().v;
    d.tick();
    ++steps;
  }
  EXPECT_EQ(f.last_command().v, 0.0);
  EXPECT_EQ(f.status().stop_reason, StopReason::kStaleOdometry);
  // Stopped within the timeout plus the braking time at stop_decel.
  // (the command may still grow during the timeout itself)
  EXPECT_LE(steps * kDt, o.odometry_timeout + (v0 + o.limits.a_max * o.odometry_timeout) / o.stop_decel + 2 * kDt);
}

// The base stops on its own while the follower's controlled stop is still ramping its command
// down (a drive fault or the base's deadman in a host stall, with the odometry stale meanwhile).
// When the base comes back the robot stands: the stop must not hand it the rest of the ramp (a
// stale command that drove a robot at rest again, seen in the fault bench).
TEST(Follower, StopHoldsARobotTheBaseAlreadyStopped)
{
  LineDrive d(8.0);
  for (int i = 0; i < 60; ++i) {
    const OdometryInput odo = d.odometry();
    d.f.step(d.now, kDt, &odo);
    d.f.refresh(1, d.now);
    d.plant.advance(d.f.last_command(), kDt);
    d.tick();
  }
  ASSERT_GT(d.f.last_command().v, 0.3);
  // The odometry freezes past its timeout and the base quick-stops the robot meanwhile.
  const OdometryInput frozen = d.odometry();
  for (int i = 0; i * kDt <= d.o.odometry_timeout + 2 * kDt; ++i) {
    d.f.step(d.now, kDt, &frozen);
    d.f.refresh(1, d.now);
    d.tick();
  }
  ASSERT_EQ(d.f.status().stop_reason, StopReason::kStaleOdometry);
  ASSERT_GT(d.f.last_command().v, 0.1) << "the ramp must still be under way for this test to mean anything";
  d.plant.v = 0.0;
  d.plant.omega = 0.0;
  // The base is back, its odometry fresh and at rest.
  const geometry::Pose2 stood = d.plant.pose;
  double v_max_after = 0.0;
  for (int i = 0; i < 40; ++i) {
    const OdometryInput odo = d.odometry();
    d.f.step(d.now, kDt, &odo);
    d.f.refresh(1, d.now);
    v_max_after = std::max(v_max_after, d.f.last_command().v);
    d.plant.advance(d.f.last_command(), kDt);
    d.tick();
  }
  EXPECT_EQ(v_max_after, 0.0);
  EXPECT_LT((d.plant.pose.translation() - stood.translation()).norm(), 1e-6);
  EXPECT_EQ(d.f.status().state, FollowerState::kIdle);
}

TEST(Follower, StaleTrajectoryStops)
{
  LineDrive d(20.0);
  bool stopped = false;
  for (int i = 0; i < 200 && !stopped; ++i) {
    d.unrefreshed_period();
    stopped = d.f.status().stop_reason == StopReason::kStaleTrajectory && d.f.last_command().v == 0.0;
  }
  EXPECT_TRUE(stopped);
  EXPECT_LT(d.plant.pose.x(), 20.0);
}

TEST(Follower, EmptyTrajectoryCancels)
{
  LineDrive d(20.0);
  for (int i = 0; i < 40; ++i) d.unrefreshed_period();
  ASSERT_GT(d.f.last_command().v, 0.2);
  d.f.replace(make_plan(make_trajectory(Chain(), 2), d.o, 0.0), d.now);
  for (int i = 0; i < 40; ++i) d.unrefreshed_period(/*plant_moves=*/false);
  EXPECT_EQ(d.f.last_command().v, 0.0);
  EXPECT_EQ(d.f.status().state, FollowerState::kIdle);
}

}  // namespace
}  // namespace rgnav::lld

namespace rgnav::lld {
namespace {

// The loop's own lateness since the newest odometry is credited to that odometry's age, up to
// the cap; a new odometry starts afresh, a loop on time earns nothing, a gap over the cap voids it.
TEST(StallCredit, CountsTheLoopsLatenessSinceTheNewestOdometry)
{
  StallCredit c(0.4);
  const time::Time a = time::from_utime(1'000'000), b = time::from_utime(1'020'000);
  c.on_tick(0.02, 0.02, a);
  EXPECT_DOUBLE_EQ(c.credit_s(), 0.0);
  c.on_tick(0.17, 0.02, a);   // the host stood still for 150 ms
  EXPECT_NEAR(c.credit_s(), 0.15, 1e-12);
  c.on_tick(0.02, 0.02, a);   // on time again: the credit stays while the odometry is the same
  EXPECT_NEAR(c.credit_s(), 0.15, 1e-12);
  c.on_tick(0.02, 0.02, b);   // new odometry
  EXPECT_DOUBLE_EQ(c.credit_s(), 0.0);
  for (int i = 0; i < 10; ++i) c.on_tick(0.22, 0.02, b);
  EXPECT_DOUBLE_EQ(c.credit_s(), 0.4);
  c.on_tick(0.72, 0.02, b);   // one gap longer than the cap: the process was stopped, no excuse
  EXPECT_DOUBLE_EQ(c.credit_s(), 0.0);
}

}  // namespace
}  // namespace rgnav::lld
