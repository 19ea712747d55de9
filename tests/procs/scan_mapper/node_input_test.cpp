// Hostile and broken inputs through the FakeBus, past the publisher's checks: NaN and
// infinite ranges, zero or negative angle steps, beam counts that do not fit the angles,
// absurd geometry, time going back or leaping ahead, NaN and far-away odometry. Each is
// dropped and counted; the node neither crashes nor lets any reach its map or its state:
// the map built with them interleaved is exactly the map built without them.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <limits>

#include "node_harness.h"
#include "scan_mapper/input_checks.h"

namespace sm = rgnav::scan_mapper;
namespace fs = std::filesystem;
using rgnav::laser_scan_t;
using rgnav::odometry_t;
using sm::testing::drive_odometry;
using sm::testing::drive_scan;
using sm::testing::NodeHarness;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// Every way a decodable scan can be wrong, made from the good scan of step i.
std::vector<laser_scan_t> hostile_scans(int i)
{
  std::vector<laser_scan_t> out;
  const auto base = drive_scan(i, 100000);  // an id that would be fresh
  auto mod = [&](auto f) {
    auto m = base;
    f(m);
    out.push_back(m);
  };
  mod([](laser_scan_t& m) { m.ranges[10] = kNaN; });
  mod([](laser_scan_t& m) { m.ranges[20] = kInf; });
  mod([](laser_scan_t& m) { m.ranges[30] = -1.f; });
  mod([](laser_scan_t& m) { m.angle_increment = 0.f; });
  mod([](laser_scan_t& m) { m.angle_increment = -0.01f; });
  mod([](laser_scan_t& m) { m.angle_increment = kNaN; });
  mod([](laser_scan_t& m) { m.angle_min = 1e30f; });
  mod([](laser_scan_t& m) { m.range_max = 1e30f; });
  mod([](laser_scan_t& m) { m.range_min = m.range_max + 1.f; });
  mod([](laser_scan_t& m) {  // 5000 beams at one degree: more than a turn
    m.nranges = 5000;
    m.ranges.assign(5000, 2.f);
  });
  mod([](laser_scan_t& m) { m.scan_id = 0; });
  mod([](laser_scan_t& m) { m.utime = -5; });
  mod([](laser_scan_t& m) { m.utime = 1'000'000 + (static_cast<int64_t>(1) << 60); });
  mod([](laser_scan_t& m) { m.utime -= 3'000'000; });  // back in time
  return out;
}

std::vector<odometry_t> hostile_odometry(int i)
{
  std::vector<odometry_t> out;
  const auto base = drive_odometry(i);
  auto mod = [&](auto f) {
    auto m = base;
    f(m);
    out.push_back(m);
  };
  mod([](odometry_t& m) { m.odom_from_base.x = std::numeric_limits<double>::quiet_NaN(); });
  mod([](odometry_t& m) { m.odom_from_base.theta = std::numeric_limits<double>::infinity(); });
  mod([](odometry_t& m) { m.odom_from_base.x = 1e30; });
  mod([](odometry_t& m) { m.odom_from_base.y = -5e6; });
  mod([](odometry_t& m) { m.utime = static_cast<int64_t>(1) << 62; });        // absurd future
  mod([](odometry_t& m) { m.utime += 3'600'000'000; });  // an hour ahead, once
  mod([](odometry_t& m) { m.utime -= 2'000'000; });                           // back in time
  return out;
}

struct Outcome
{
  std::vector<sm::ScanNode> nodes;
  int64_t drops = 0;
  size_t aligned = 0;
};

Outcome run(bool hostile, const sm::PersistenceOptions& p)
{
  NodeHarness h(p);
  for (int i = 0; i < 120; ++i) {
    rgnav::bus::publish(h.node->bus(), "ODOMETRY", drive_odometry(i));
    if (hostile && i % 10 == 5)
      for (const auto& o : hostile_odometry(i)) h.send_raw("ODOMETRY", o);
    if (hostile && i % 10 == 7)
      for (const auto& s : hostile_scans(i)) h.send_raw("LASER_FRONT", s);
    rgnav::bus::publish(h.node->bus(), "LASER_FRONT", drive_scan(i));
    h.settle();
  }
  Outcome out;
  out.nodes = h.adapter->mapper().nodes();
  out.drops = h.node->drops().total();
  out.aligned = h.published<rgnav::aligned_scan_t>("ALIGNED_SCAN").size();
  return out;
}

}  // namespace

TEST(ScanMapperNodeInput, HostileMessagesAreDroppedAndNeverReachTheMap)
{
  const auto dir = fs::temp_directory_path() / ("rgnav_sm_hostile_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  sm::PersistenceOptions p;
  p.state_file = (dir / "state.bin").string();
  p.snapshot_every_records = 7;
  const Outcome clean = run(false, {});
  const Outcome dirty = run(true, p);
  ASSERT_GT(clean.nodes.size(), 20u);
  EXPECT_EQ(clean.drops, 0);
  // Every hostile message was dropped (12 rounds of 14 scans and 7 odometry samples), save
  // the hour-ahead odometry sample that the next good one shows to be wrong: also dropped.
  EXPECT_EQ(dirty.drops, 12 * (14 + 7));
  ASSERT_EQ(dirty.nodes.size(), clean.nodes.size());
  EXPECT_EQ(dirty.aligned, clean.aligned);
  for (size_t i = 0; i < clean.nodes.size(); ++i) {
    EXPECT_EQ(dirty.nodes[i].scan.scan_id, clean.nodes[i].scan.scan_id);
    EXPECT_EQ(dirty.nodes[i].map_from_base.x(), clean.nodes[i].map_from_base.x()) << i;
    EXPECT_EQ(dirty.nodes[i].map_from_base.y(), clean.nodes[i].map_from_base.y()) << i;
  }
  // The persisted state is the clean one too.
  NodeHarness again(p);
  EXPECT_TRUE(again.adapter->recovery()->damage.empty());
  EXPECT_EQ(again.adapter->mapper().nodes().size(), clean.nodes.size());
  fs::remove_all(dir);
}

TEST(ScanMapperNodeInput, OdometryTimeJumpIsBelievedOnceConfirmed)
{
  NodeHarness h(sm::PersistenceOptions{});
  sm::testing::drive(h, 0, 20);
  const size_t before = h.adapter->mapper().nodes().size();
  // The clock really jumped (a log replayed after a pause): two samples confirm it.
  const int64_t jump = 600'000'000;
  for (int i = 20; i < 60; ++i) {
    auto o = drive_odometry(i);
    o.utime += jump;
    rgnav::bus::publish(h.node->bus(), "ODOMETRY", o);
    auto s = drive_scan(i);
    s.utime += jump;
    rgnav::bus::publish(h.node->bus(), "LASER_FRONT", s);
    h.settle();
  }
  EXPECT_EQ(h.node->drops().total(), 1);  // the first sample after the jump only
  EXPECT_GT(h.adapter->mapper().nodes().size(), before + 5);
}

TEST(ScanMapperInput, LibraryRefusesWhatTheChecksRefuse)
{
  sm::ScanMapper mapper(sm::testing::node_test_options());
  mapper.add_odometry({1'000'000, sm::Pose2{std::nan(""), 0, 0}});
  mapper.add_odometry({1'000'000, sm::Pose2{0, 0, 0}});
  auto scan = rgnav::msg::to_laser_scan(drive_scan(0));
  scan.utime = 1'000'000;
  scan.ranges[3] = kNaN;
  EXPECT_FALSE(mapper.add_scan(scan).accepted);
  EXPECT_EQ(mapper.stats().invalid, 2);
  EXPECT_TRUE(mapper.nodes().empty());
  EXPECT_EQ(sm::check_scan(rgnav::msg::to_laser_scan(drive_scan(0))), "");
}
