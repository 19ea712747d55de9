#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "box_world.h"
#include "sim/simulator.h"
#include "sim/synchro_drive.h"

namespace rgnav::sim {
namespace {

using std::chrono::microseconds;

// A fixed command for tests.
class Constant final : public DriveCommandSource
{
 public:
  explicit Constant(DriveCommand c) : c_(c) {}
  std::optional<DriveCommand> command_at(int64_t) override { return c_; }
  DriveCommand c_;
};

using rgnav::testing::box_world;

SimulatorOptions quiet_options()
{
  SimulatorOptions o;
  o.laser.noise_sigma = 0.0;
  return o;
}

TEST(SynchroDrive, RespectsAccelerationAndVelocityLimits)
{
  SynchroDriveOptions o;
  o.v_max = 0.9;
  o.omega_max = 2.0;
  o.accel = 0.8;
  o.alpha = 2.5;
  SynchroDrive d(o);
  const double dt = 0.001;
  double prev_v = 0, prev_w = 0;
  for (int i = 0; i < 3000; ++i) {
    d.step({5.0, -9.0}, dt);
    EXPECT_LE(std::fabs(d.v() - prev_v), o.accel * dt + 1e-12);
    EXPECT_LE(std::fabs(d.omega() - prev_w), o.alpha * dt + 1e-12);
    prev_v = d.v();
    prev_w = d.omega();
  }
  EXPECT_DOUBLE_EQ(d.v(), 0.9);
  EXPECT_DOUBLE_EQ(d.omega(), -2.0);
  // Independent axes: rotation reached its limit long before translation did.
  SynchroDrive e(o);
  BaseMotion total;
  for (int i = 0; i < 1000; ++i) {
    const auto m = e.step({0.5, 0.0}, dt);
    total.ds += m.ds;
    total.dtheta += m.dtheta;
  }
  // 0.5 m/s reached after 0.625 s: distance = 0.5 * 0.625 / 2 + 0.5 * 0.375.
  EXPECT_NEAR(total.ds, 0.15625 + 0.1875, 1e-6);
  EXPECT_EQ(total.dtheta, 0.0);
}

// The body speeds up on the motor's ramp but brakes as hard as the drive commands, up to its
// grip: a quick stop is not slowed to the cruise acceleration.
TEST(SynchroDrive, BehindRampingDrivesBrakesAtItsBrakingLimitAndSpeedsUpAtItsAcceleration)
{
  SynchroDriveOptions o;
  o.accel = 0.8;
  o.brake_decel = 4.5;
  const double dt = 0.001;
  SynchroDrive d(o);
  while (d.v() < 0.6) d.step({0.6, 0.0}, dt, true);
  // Commanded zero at once: at rest after v / brake_decel, over v^2 / (2 brake_decel).
  double ds = 0.0;
  int steps = 0;
  double prev = d.v();
  while (d.v() > 0.0 && steps < 10000) {
    ds += d.step({0.0, 0.0}, dt, true).ds;
    EXPECT_LE(prev - d.v(), o.brake_decel * dt + 1e-12);
    prev = d.v();
    ++steps;
  }
  EXPECT_NEAR(steps * dt, 0.6 / 4.5, 2 * dt);
  EXPECT_NEAR(ds, 0.6 * 0.6 / (2 * 4.5), 1e-3);
  // Slowing to a lower speed brakes too; speeding up again is on the cruise ramp.
  SynchroDrive e(o);
  while (e.v() < 0.6) e.step({0.6, 0.0}, dt, true);
  e.step({0.2, 0.0}, 0.05, true);
  EXPECT_NEAR(e.v(), 0.6 - 4.5 * 0.05, 1e-9);
  e.step({0.2, 0.0}, 0.05, true);
  EXPECT_NEAR(e.v(), 0.2, 1e-9);
  e.step({0.6, 0.0}, 0.05, true);
  EXPECT_NEAR(e.v(), 0.2 + 0.8 * 0.05, 1e-9);
  // A reversal within one step: braking to zero, then the rest of the step speeding up backwards.
  SynchroDrive r(o);
  while (r.v() < 0.45) r.step({0.45, 0.0}, dt, true);
  r.step({-0.5, 0.0}, 0.2, true);  // 0.1 s to stop, 0.1 s at 0.8 m/s^2 backwards
  EXPECT_NEAR(r.v(), -0.08, 1e-9);
  // Raw commands (direct mode): the simulated drive ramps them at its cruise accel both ways.
  SynchroDrive raw(o);
  while (raw.v() < 0.6) raw.step({0.6, 0.0}, dt);
  const double v_raw = raw.v();
  raw.step({0.0, 0.0}, 0.05);
  EXPECT_NEAR(raw.v(), v_raw - 0.8 * 0.05, 1e-9);
}

TEST(SynchroDrive, ArcsAreExact)
{
  // A full circle of radius 1 comes back to the start.
  Pose2 p{0, 0, 0};
  for (int i = 0; i < 1000; ++i) p = apply_motion(p, 2 * M_PI / 1000, 2 * M_PI / 1000);
  EXPECT_NEAR(p.x, 0.0, 1e-9);
  EXPECT_NEAR(p.y, 0.0, 1e-9);
  const Pose2 q = apply_motion({0, 0, 0}, M_PI / 2, M_PI / 2);  // quarter circle, radius 1
  EXPECT_NEAR(q.x, 1.0, 1e-12);
  EXPECT_NEAR(q.y, 1.0, 1e-12);
}

TEST(Odometry, SystematicAndRandomErrorStatistics)
{
  // 200 runs of 10 m straight: the mean error is the scale error, the spread grows as
  // sigma * sqrt(distance), the heading drifts by the bias.
  OdometryErrorOptions o;
  o.scale_translation = 0.02;
  o.sigma_translation = 0.01;
  o.bias_rotation_per_m = 0.003;
  o.sigma_rotation_per_m = 0.002;
  const int runs = 200;
  double sum = 0, sum2 = 0, heading = 0, heading2 = 0;
  for (int r = 0; r < runs; ++r) {
    OdometryModel odo(o, Rng::derive(5, static_cast<uint64_t>(r)));
    for (int k = 0; k < 1000; ++k) odo.integrate({0.01, 0.0});
    const double e = odo.translation_total() - 10.0;
    sum += e;
    sum2 += e * e;
    heading += odo.rotation_total();
    heading2 += odo.rotation_total() * odo.rotation_total();
  }
  const double mean = sum / runs, sd = std::sqrt(sum2 / runs - mean * mean);
  EXPECT_NEAR(mean, 0.2, 0.01);                    // 2 % of 10 m (sd of the mean: 0.0022)
  EXPECT_NEAR(sd, 0.01 * std::sqrt(10.0), 0.01);   // 0.0316
  const double hmean = heading / runs, hsd = std::sqrt(heading2 / runs - hmean * hmean);
  EXPECT_NEAR(hmean, 0.03, 0.002);
  EXPECT_NEAR(hsd, 0.002 * std::sqrt(10.0), 0.002);
}

TEST(Odometry, ErrorStatisticsDoNotDependOnStepSize)
{
  OdometryErrorOptions o;
  o.sigma_translation = 0.02;
  auto spread = [&](int steps) {
    double s2 = 0;
    for (int r = 0; r < 300; ++r) {
      OdometryModel odo(o, Rng::derive(11, static_cast<uint64_t>(r)));
      for (int k = 0; k < steps; ++k) odo.integrate({4.0 / steps, 0.0});
      s2 += std::pow(odo.translation_total() - 4.0, 2);
    }
    return std::sqrt(s2 / 300);
  };
  EXPECT_NEAR(spread(40), 0.04, 0.008);
  EXPECT_NEAR(spread(4000), 0.04, 0.008);
}

TEST(Collision, RobotStopsAtTheWallAndNeverPassesThrough)
{
  World w = box_world(3.0);
  w.start = {0, 0, 0};
  Simulator sim(w, quiet_options());
  Constant forward({0.9, 0.0});
  sim.set_command_source(&forward);
  std::vector<CollisionEvent> events;
  for (int i = 0; i < 100; ++i) {
    auto out = sim.step(microseconds(100000));
    for (auto& e : out.collisions) events.push_back(e);
    EXPECT_LE(sim.truth().x, 3.0 - 0.26 + 1e-6);
  }
  ASSERT_EQ(events.size(), 1u) << "one contact, reported once";
  EXPECT_EQ(events[0].with, "wall[1]");
  EXPECT_NEAR(sim.truth().x, 3.0 - 0.26, 1e-3);
  EXPECT_EQ(sim.drive().v(), 0.0);
  EXPECT_EQ(sim.collisions(), 1);
  // Backing out is allowed.
  Constant back({-0.3, 0.0});
  sim.set_command_source(&back);
  sim.step(microseconds(2'000'000));
  EXPECT_LT(sim.truth().x, 3.0 - 0.26 - 0.2);
}

TEST(Collision, TabletopStopsTheBodyAlthoughTheLaserMissesIt)
{
  World w = box_world(6.0);
  Table t;
  t.name = "desk";
  t.center = {2.0, 0.0};
  t.size = {1.2, 0.8};
  w.tables.push_back(t);
  Simulator sim(w, quiet_options());
  Constant forward({0.5, 0.0});
  sim.set_command_source(&forward);
  StepOutput out = sim.step(microseconds(6'000'000));
  ASSERT_FALSE(out.collisions.empty());
  EXPECT_EQ(out.collisions[0].with, "desk.top");
  EXPECT_NEAR(sim.truth().x, 1.4 - 0.26, 1e-3);
  // The last scan's centre beam sees the far wall, not the table (legs are off-axis).
  ASSERT_FALSE(out.scans.empty());
  EXPECT_GT(out.scans.back().ranges[90], 4.0);
}

TEST(Commands, StaleCommandDeceleratesToAStop)
{
  World w = box_world(20.0);
  SimulatorOptions o = quiet_options();
  Simulator sim(w, o);
  TimedCommandSource cmd;
  sim.set_command_source(&cmd);
  cmd.set(sim.now_utime(), {0.8, 0.0}, 2'000'000);
  StepOutput out = sim.step(microseconds(1'500'000));
  EXPECT_NEAR(sim.drive().v(), 0.8, 1e-9);
  EXPECT_TRUE(out.odometry.back().commanded);
  // The deadline passes at 2 s; with 0.8 m/s^2 the drive is at rest 1 s later.
  out = sim.step(microseconds(600'000));
  EXPECT_LT(sim.drive().v(), 0.8);
  EXPECT_GT(sim.drive().v(), 0.0);
  EXPECT_FALSE(out.odometry.back().commanded);
  sim.step(microseconds(1'000'000));
  EXPECT_EQ(sim.drive().v(), 0.0);
  const double x = sim.truth().x;
  sim.step(microseconds(1'000'000));
  EXPECT_EQ(sim.truth().x, x);
}

TEST(Simulator, RatesOfScansAndOdometry)
{
  Simulator sim(box_world(), quiet_options());
  const StepOutput out = sim.step(microseconds(2'000'000));
  EXPECT_EQ(out.scans.size(), 150u);  // 75 Hz
  EXPECT_EQ(out.odometry.size(), 100u);  // 50 Hz
  for (size_t i = 1; i < out.scans.size(); ++i) {
    EXPECT_EQ(out.scans[i].scan_id, out.scans[i - 1].scan_id + 1);
    EXPECT_NEAR(out.scans[i].utime - out.scans[i - 1].utime, 13333, 1);
  }
  // Interlaced 0.5 deg: 37.5 Hz.
  SimulatorOptions o = quiet_options();
  o.laser.beams = 361;
  Simulator fine(box_world(), o);
  EXPECT_EQ(fine.step(microseconds(2'000'000)).scans.size(), 75u);
}

TEST(People, WalkTheirPathsAndAreSeen)
{
  World w = box_world(8.0);
  w.start = {-6, 0, 0};
  Person p;
  p.name = "walker";
  p.path = {{2, -4}, {2, 4}};
  p.speed = 1.0;
  p.loop = false;
  w.people.push_back(p);
  Simulator sim(w, quiet_options());
  const Vec2 at0 = sim.people()[0].center;
  sim.step(microseconds(3'000'000));
  const Vec2 at3 = sim.people()[0].center;
  EXPECT_NEAR(at3.y() - at0.y(), 3.0, 1e-6);
  // Back and forth: after 8 m it is at the far end, after 11 m it has walked 3 m back.
  sim.step(microseconds(8'000'000));
  EXPECT_NEAR(sim.people()[0].center.y(), 1.0, 1e-6);
  // The laser sees it when it crosses the beam: at y = 0 the centre beam reads 8 - 0.22 - 0.12.
  World still = box_world(8.0);
  still.start = {-6, 0, 0};
  Person s;
  s.path = {{2, 0}};
  still.people.push_back(s);
  Simulator sim2(still, quiet_options());
  const StepOutput out = sim2.step(microseconds(20000));
  ASSERT_FALSE(out.scans.empty());
  EXPECT_NEAR(out.scans[0].ranges[90], 8.0 - 0.22 - 0.12, 0.0011);
}

TEST(People, WaitForTheRobotAtTheirPersonalSpace)
{
  // A person walking straight at the standing robot (start -6,0; radius 0.26) stops touching
  // it without a personal space, 0.4 m from it with one, and never walks on into it.
  for (const double space : {0.0, 0.4}) {
    World w = box_world(8.0);
    w.start = {-6, 0, 0};
    Person p;
    p.path = {{2, 0}, {-7.5, 0}};
    p.speed = 1.0;
    p.loop = false;
    p.personal_space = space;
    w.people.push_back(p);
    Simulator sim(w, quiet_options());
    sim.step(microseconds(12'000'000));
    const double gap = (sim.people()[0].center - Vec2(-6, 0)).norm() - p.radius - 0.26;
    EXPECT_GE(gap, space - 1e-9) << space;
    EXPECT_LT(gap, space + 0.05) << space;
    EXPECT_EQ(sim.collisions(), 0);
  }
  // Walking away from the robot nobody waits.
  World w = box_world(8.0);
  w.start = {-6, 0, 0};
  Person away;
  away.path = {{-5.2, 0}, {3, 0}};
  away.speed = 1.0;
  away.loop = false;
  away.personal_space = 0.4;
  w.people.push_back(away);
  Simulator sim(w, quiet_options());
  sim.step(microseconds(2'000'000));
  EXPECT_NEAR(sim.people()[0].center.x(), -3.2, 1e-6);
}

// A hallway along x, `width` wide, 16 m long, the robot standing in its middle at (-2, 0).
World hallway_with_robot(double width)
{
  World w;
  for (const double y : {-0.5 * width, 0.5 * width}) {
    Wall wall;
    wall.a = {-8, y};
    wall.b = {8, y};
    w.walls.push_back(wall);
  }
  w.start = {-2, 0, 0};
  return w;
}

TEST(People, StepAroundTheRobotAfterTheirPatienceWhereThereIsRoom)
{
  // Someone walking down a 2 m hallway at the robot standing in its middle waits at the
  // personal space for their patience, then steps around it, passes it without touching,
  // and is back on their line further on. In a 1.2 m hallway there is no room: they wait on.
  for (const double width : {2.0, 1.2}) {
    World w = hallway_with_robot(width);
    Person p;
    p.path = {{4, 0}, {-7.5, 0}};
    p.speed = 1.0;
    p.loop = false;
    p.personal_space = 0.4;
    p.patience = 3.0;
    w.people.push_back(p);
    Simulator sim(w, quiet_options());
    // 5.1 m to the personal space (~5.1 s), then 3 s of patience.
    sim.step(microseconds(7'500'000));
    const double waiting_gap = (sim.people()[0].center - Vec2(-2, 0)).norm() - p.radius - 0.26;
    EXPECT_NEAR(waiting_gap, 0.4, 0.05) << width;
    double closest = std::numeric_limits<double>::infinity(), widest = 0.0;
    for (int k = 0; k < 100; ++k) {
      sim.step(microseconds(100'000));
      const Vec2 c = sim.people()[0].center;
      closest = std::min(closest, (c - Vec2(-2, 0)).norm() - p.radius - 0.26);
      widest = std::max(widest, std::fabs(c.y()) + p.radius);
    }
    EXPECT_EQ(sim.collisions(), 0) << width;
    EXPECT_GE(closest, 0.0) << width;
    EXPECT_LE(widest, 0.5 * width) << width << ": never into a wall";
    if (width > 1.5) {
      EXPECT_LT(sim.people()[0].center.x(), -3.0) << "passed the robot";
      sim.step(microseconds(3'000'000));
      EXPECT_NEAR(sim.people()[0].center.y(), 0.0, 1e-6) << "back on the line";
    } else {
      EXPECT_GE(closest, 0.4 - 1e-9) << "still waiting at the personal space";
    }
  }
}

TEST(People, ThatDoNotBlockTheRobotAreSeenAndPassedThrough)
{
  // Benchmarks of perception (people_block_robot: false): a person standing in the robot's way
  // is in the scans, but neither stops the robot nor waits for it.
  for (const bool block : {true, false}) {
    World w = box_world(8.0);
    w.start = {-6, 0, 0};
    Person p;
    p.path = {{0, 0}};
    w.people.push_back(p);
    SimulatorOptions o = quiet_options();
    o.people_block_robot = block;
    Simulator sim(w, o);
    Constant forward({0.5, 0.0});
    sim.set_command_source(&forward);
    const StepOutput first = sim.step(microseconds(20000));
    ASSERT_FALSE(first.scans.empty());
    EXPECT_NEAR(first.scans[0].ranges[90], 6.0 - 0.22 - 0.12, 0.01) << block;
    sim.step(microseconds(20'000'000));
    if (block) {
      EXPECT_EQ(sim.collisions(), 1);
      EXPECT_LT(sim.truth().x, -0.22 - 0.26 + 1e-3);
    } else {
      EXPECT_EQ(sim.collisions(), 0);
      EXPECT_GT(sim.truth().x, 1.0);
    }
  }
}

TEST(Doors, ScheduledDoorClosesDuringTheRun)
{
  World w = box_world(8.0);
  Door d;
  d.name = "d";
  d.hinge = {3, -0.5};
  d.latch = {3, 0.5};
  d.open = true;
  d.schedule = {{1.0, false}};
  w.doors.push_back(d);
  Simulator sim(w, quiet_options());
  StepOutput out = sim.step(microseconds(500'000));
  EXPECT_GT(out.scans.back().ranges[90], 7.0);
  out = sim.step(microseconds(1'000'000));
  EXPECT_NEAR(out.scans.back().ranges[90], 3.0 - 0.12, 0.0011);
}

}  // namespace
}  // namespace rgnav::sim
