#include "collision_avoidance/ca_node.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <random>

#include "bus/fake_bus.h"
#include "collision_avoidance/chain_planner.h"
#include "msg/conversions.h"
#include "rgnav/ca_status_t.hpp"
#include "rgnav/heartbeat_t.hpp"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/target_list_t.hpp"
#include "rgnav/trajectory_t.hpp"
#include "scan_fixture.h"
#include "trajectory/trajectory_conversions.h"

namespace rgnav::collision_avoidance {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

laser_scan_t scan_msg(int64_t utime, int64_t id, const std::vector<testing::Wall>& walls)
{
  laser_scan_t m{};
  m.utime = utime;
  m.scan_id = id;
  m.sensor = "laser_front";
  m.angle_min = static_cast<float>(-M_PI_2);
  m.angle_increment = static_cast<float>(M_PI / 180.0);
  m.range_min = 0.02f;
  m.range_max = 8.0f;
  m.scan_time = 1.0f / 75;
  // The laser sits 0.12 m ahead of the base (config default) at the odom origin.
  for (const auto& r : testing::cast(geometry::Pose2(0.12, 0, 0), walls)) m.ranges.push_back(static_cast<float>(r.range));
  m.nranges = static_cast<int32_t>(m.ranges.size());
  return m;
}

odometry_t odo_msg(int64_t utime, int64_t seq)
{
  odometry_t m{};
  m.utime = utime;
  m.seq = seq;
  m.status = odometry_t::STATUS_OK;
  return m;
}

template <class T>
std::vector<uint8_t> encoded(const T& m)
{
  std::vector<uint8_t> out(static_cast<size_t>(m.getEncodedSize()));
  m.encode(out.data(), 0, static_cast<int>(out.size()));
  return out;
}

target_list_t target_msg(const std::vector<geometry::Pose2>& poses)
{
  target_list_t m{};
  m.utime = kT0;
  m.goal_id = 1;
  for (const auto& p : poses) m.odom_from_target.push_back(msg::to_msg(p));
  m.ntargets = static_cast<int32_t>(m.odom_from_target.size());
  m.max_speed = 0.5f;
  m.final_is_goal = true;
  return m;
}

struct Fixture
{
  bus::FakeBus* fake;
  std::unique_ptr<runtime::Node> node;
  std::unique_ptr<CaNode> ca;

  Fixture()
  {
    auto bus = std::make_unique<bus::FakeBus>();
    fake = bus.get();
    runtime::NodeOptions no;
    no.name = "collision_avoidance";
    node = std::make_unique<runtime::Node>(no, std::move(bus));
    ca = std::make_unique<CaNode>(*node, CaNodeOptions{});
  }
  std::vector<trajectory::Trajectory> trajectories() const
  {
    std::vector<trajectory::Trajectory> out;
    for (const auto& p : fake->published_on("TRAJECTORY")) {
      trajectory_t m;
      std::string why;
      EXPECT_TRUE(bus::decode(p.data.data(), p.data.size(), &m, &why)) << why;
      auto t = trajectory::from_msg(m, &why);
      EXPECT_TRUE(t) << why;
      if (t) out.push_back(*t);
    }
    return out;
  }
  void targets(const std::vector<geometry::Pose2>& poses) { ASSERT_TRUE(bus::publish(*fake, "TARGETS", target_msg(poses))); }
};

const std::vector<testing::Wall> kCorridor = {{{-1, -1.5}, {12, -1.5}}, {{-1, 1.5}, {12, 1.5}}};

TEST(CaNode, PlansAroundABoxOverTheBus)
{
  Fixture f;
  auto walls = kCorridor;
  for (const auto& w : testing::box(1.3, -0.3, 1.7, 0.3)) walls.push_back(w);
  ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(kT0, 1)));
  ASSERT_TRUE(bus::publish(*f.fake, "LASER_FRONT", scan_msg(kT0, 1, walls)));
  f.targets({geometry::Pose2(1.0, 0.0, 0.0), geometry::Pose2(2.0, 0.0, 0.0), geometry::Pose2(3.0, 0.0, 0.0)});
  ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(kT0 + 20'000, 2)));
  const auto ts = f.trajectories();
  ASSERT_FALSE(ts.empty());
  const auto& t = ts.back();
  ASSERT_FALSE(t.chain.empty());
  // Never into the box: the whole chain keeps the footprint clear of the scanned obstacles.
  const auto& map = f.ca->ca().map();
  EXPECT_FALSE(first_collision(t.chain, map, 0.26, 0.01));
  EXPECT_EQ(f.ca->ca().mode(), Mode::kPlanned);
}

TEST(CaNode, BlockedCorridorStopsAndReports)
{
  Fixture f;
  auto walls = kCorridor;
  walls.push_back({{0.9, -1.5}, {0.9, 1.5}});  // closed 0.9 m ahead
  ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(kT0, 1)));
  ASSERT_TRUE(bus::publish(*f.fake, "LASER_FRONT", scan_msg(kT0, 1, walls)));
  f.targets({geometry::Pose2(1.5, 0.0, 0.0), geometry::Pose2(2.5, 0.0, 0.0)});
  const auto ts = f.trajectories();
  ASSERT_FALSE(ts.empty());
  for (const auto& t : ts) {
    // Only stops or turns on the spot: nothing drives toward the wall.
    for (const auto& s : t.chain.segments()) EXPECT_EQ(s.kind(), trajectory::Kind::kTurn);
  }
  EXPECT_EQ(f.ca->ca().mode(), Mode::kReactive);
  f.node->publish_heartbeat();
  heartbeat_t hb;
  std::string why;
  const auto hbs = f.fake->published_on("HEARTBEAT");
  ASSERT_FALSE(hbs.empty());
  ASSERT_TRUE(bus::decode(hbs.back().data.data(), hbs.back().data.size(), &hb, &why));
  EXPECT_EQ(hb.state, heartbeat_t::STATE_DEGRADED);
  EXPECT_NE(hb.status.find("reactive"), std::string::npos);
}

TEST(CaNode, StaleScansStop)
{
  Fixture f;
  ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(kT0, 1)));
  ASSERT_TRUE(bus::publish(*f.fake, "LASER_FRONT", scan_msg(kT0, 1, kCorridor)));
  f.targets({geometry::Pose2(2.0, 0.0, 0.0), geometry::Pose2(4.0, 0.0, 0.0)});
  ASSERT_FALSE(f.trajectories().empty());
  ASSERT_FALSE(f.trajectories().back().chain.empty());
  // Odometry goes on, scans do not.
  for (int i = 1; i <= 40; ++i) ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(kT0 + i * 20'000, 1 + i)));
  const auto ts = f.trajectories();
  EXPECT_TRUE(ts.back().chain.empty());  // the stop
  EXPECT_EQ(f.ca->ca().mode(), Mode::kStaleStop);
}

std::vector<ca_status_t> statuses(const bus::FakeBus& fake)
{
  std::vector<ca_status_t> out;
  for (const auto& p : fake.published_on("CA_STATUS")) {
    ca_status_t m;
    std::string why;
    EXPECT_TRUE(bus::decode(p.data.data(), p.data.size(), &m, &why)) << why;
    out.push_back(m);
  }
  return out;
}

TEST(CaNode, StatusSaysHowLongItCouldNotPass)
{
  Fixture f;
  auto walls = kCorridor;
  walls.push_back({{0.9, -1.5}, {0.9, 1.5}});  // closed 0.9 m ahead
  ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(kT0, 1)));
  ASSERT_TRUE(bus::publish(*f.fake, "LASER_FRONT", scan_msg(kT0, 1, walls)));
  f.targets({geometry::Pose2(1.5, 0.0, 0.0), geometry::Pose2(2.5, 0.0, 0.0)});
  // Three seconds of fresh scans and odometry while the corridor stays closed.
  for (int i = 1; i <= 150; ++i) {
    ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(kT0 + i * 20'000, 1 + i)));
    if (i % 5 == 0) {
      ASSERT_TRUE(bus::publish(*f.fake, "LASER_FRONT", scan_msg(kT0 + i * 20'000, 1 + i / 5, walls)));
    }
  }
  const auto s = statuses(*f.fake);
  ASSERT_FALSE(s.empty());
  // At 2 Hz of message time, plus one per change of mode: a few, not one per odometry sample.
  EXPECT_GE(s.size(), 6u);
  EXPECT_LE(s.size(), 20u);
  const auto& last = s.back();
  EXPECT_EQ(last.goal_id, 1);
  EXPECT_TRUE(last.mode == ca_status_t::MODE_REACTIVE || last.mode == ca_status_t::MODE_BLOCKED) << int(last.mode);
  EXPECT_GT(last.blocked_s, 2.0);
  EXPECT_LE(last.blocked_s, 3.01);
  EXPECT_FALSE(last.status.empty());
  for (size_t i = 1; i < s.size(); ++i) EXPECT_GE(s[i].utime, s[i - 1].utime);
}

TEST(CaNode, StatusOfAFreeWayIsPlannedAndNotBlocked)
{
  Fixture f;
  ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(kT0, 1)));
  ASSERT_TRUE(bus::publish(*f.fake, "LASER_FRONT", scan_msg(kT0, 1, kCorridor)));
  f.targets({geometry::Pose2(2.0, 0.0, 0.0), geometry::Pose2(4.0, 0.0, 0.0)});
  ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(kT0 + 20'000, 2)));
  const auto s = statuses(*f.fake);
  ASSERT_FALSE(s.empty());
  EXPECT_EQ(s.back().mode, ca_status_t::MODE_PLANNED);
  EXPECT_EQ(s.back().blocked_s, 0.0);
  EXPECT_EQ(s.back().goal_id, 1);
  EXPECT_EQ(s.back().next_target, 0);
}

// A target no planner sends (1e30 m away: a corrupted list) is dropped and counted: planned
// through, it had collision avoidance sample a line of that length for ever, and the supervisor
// stopped it as hung over and over in the fault bench.
TEST(CaNode, DropsTargetsNoPlannerSends)
{
  Fixture f;
  ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(kT0, 1)));
  ASSERT_TRUE(bus::publish(*f.fake, "LASER_FRONT", scan_msg(kT0, 1, kCorridor)));
  const auto bad = encoded(target_msg({geometry::Pose2(1.0, 0.0, 0.0), geometry::Pose2(1e30, 0.0, 0.0)}));
  const int64_t before = f.node->drops().total();
  f.fake->publish("TARGETS", bad.data(), bad.size());
  EXPECT_EQ(f.node->drops().total(), before + 1);
  EXPECT_TRUE(f.trajectories().empty() || f.trajectories().back().chain.empty()) << "nothing planned toward it";
}

// A target the message checks let pass but beyond max_target_distance (20 m) is no local
// planner's: the robot stops and says why; one within it is planned to.
TEST(CaNode, StopsForATargetBeyondItsReach)
{
  for (const double x : {30.0, 8.0}) {
    Fixture f;
    ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(kT0, 1)));
    ASSERT_TRUE(bus::publish(*f.fake, "LASER_FRONT", scan_msg(kT0, 1, kCorridor)));
    f.targets({geometry::Pose2(x, 0.0, 0.0)});
    ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(kT0 + 20'000, 2)));
    const auto ts = f.trajectories();
    ASSERT_FALSE(ts.empty());
    if (x > 20.0) {
      EXPECT_TRUE(ts.back().chain.empty());
      EXPECT_EQ(f.ca->ca().mode(), Mode::kBlocked);
      EXPECT_NE(f.ca->ca().status().find("max_target_distance_m"), std::string::npos) << f.ca->ca().status();
    } else {
      EXPECT_FALSE(ts.back().chain.empty()) << f.ca->ca().status();
    }
  }
}

// The fault bench's malformed input (truncated, a byte flipped, random bytes; its seed) on every
// input collision avoidance plans from; afterwards it plans round a box as before.
TEST(CaNode, SurvivesCorruptedInputAndPlansAfter)
{
  Fixture f;
  const std::vector<std::pair<std::string, std::vector<uint8_t>>> valid = {
      {"LASER_FRONT", encoded(scan_msg(kT0, 1, kCorridor))},
      {"ODOMETRY", encoded(odo_msg(kT0, 1))},
      {"TARGETS", encoded(target_msg({geometry::Pose2(1.0, 0.0, 0.0), geometry::Pose2(2.0, 0.0, 0.0)}))}};
  for (const auto& [channel, bytes] : valid) f.fake->publish(channel, bytes.data(), bytes.size());
  std::mt19937 rng(42);
  for (int i = 0; i < 1000; ++i)
    for (const auto& [channel, bytes] : valid) {
      std::vector<uint8_t> m;
      if (i % 3 == 0) {
        m.assign(bytes.begin(), bytes.begin() + static_cast<long>(rng() % bytes.size()));
      } else if (i % 3 == 1) {
        m = bytes;
        m[8 + rng() % (m.size() - 8)] ^= static_cast<uint8_t>(1 + rng() % 255);
      } else {
        m.resize(1 + rng() % 512);
        for (auto& b : m) b = static_cast<uint8_t>(rng());
      }
      f.fake->publish(channel, m.data(), m.size());
    }
  EXPECT_GT(f.node->drops().total(), 1000);
  auto walls = kCorridor;
  for (const auto& w : testing::box(1.3, -0.3, 1.7, 0.3)) walls.push_back(w);
  const int64_t t = kT0 + 60'000'000;
  ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(t, 2)));
  ASSERT_TRUE(bus::publish(*f.fake, "LASER_FRONT", scan_msg(t, 2, walls)));
  auto targets = target_msg({geometry::Pose2(1.0, 0.0, 0.0), geometry::Pose2(2.0, 0.0, 0.0), geometry::Pose2(3.0, 0.0, 0.0)});
  targets.utime = t;
  targets.goal_id = 2;
  ASSERT_TRUE(bus::publish(*f.fake, "TARGETS", targets));
  ASSERT_TRUE(bus::publish(*f.fake, "ODOMETRY", odo_msg(t + 20'000, 3)));
  const auto ts = f.trajectories();
  ASSERT_FALSE(ts.empty());
  ASSERT_FALSE(ts.back().chain.empty()) << f.ca->ca().status();
  EXPECT_FALSE(first_collision(ts.back().chain, f.ca->ca().map(), 0.26, 0.01));
}

}  // namespace
}  // namespace rgnav::collision_avoidance
