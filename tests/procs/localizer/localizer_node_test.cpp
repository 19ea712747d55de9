// The localizer process over a FakeBus: a hand-made two-room RG map, odometry and ray-cast scans
// of a robot driving through the door. A pose request puts it on the truth and POSE follows the
// robot into the next room (with LOCALIZER_GATEWAY_PASSED); hostile requests and scans without
// odometry are dropped and counted; the estimate is saved and a restarted node resumes from it;
// the shipped config passes --check-config and a misspelt key is refused.
#include "localizer/localizer_node.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "bus/typed.h"
#include "bad_files.h"
#include "child_process.h"
#include "config/config.h"
#include "config/robot_description.h"
#include "fake_bus_node.h"
#include "msg/conversions.h"
#include "rgmap/rgmap_conversions.h"
#include "rgnav/gateway_passed_t.hpp"
#include "rgnav/heartbeat_t.hpp"
#include "rgnav/localize_request_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/region_pose_t.hpp"
#include "two_room_map.h"

namespace rgnav::localizer {
namespace {

using geometry::Pose2;

constexpr int64_t kT0 = 1'700'000'000'000'000;
constexpr double kSpeed = 0.5;            // [m/s] along +x through the door (y = 1.5)
constexpr double kOdometryScale = 1.02;   // the wheels say 2 % more than was driven

LocalizerNodeOptions shipped_options()
{
  const auto cfg = config::Config::load(RGNAV_SOURCE_DIR "/config/localizer.yaml");
  const auto robot = config::load_robot_description_file(RGNAV_SOURCE_DIR "/config/robot.yaml");
  return load_localizer_options(cfg, robot);
}

// The robot's true pose: from (1, 1.5) along +x at kSpeed, starting at kT0.
Pose2 truth_at(int64_t utime) { return Pose2(1.0 + kSpeed * static_cast<double>(utime - kT0) * 1e-6, 1.5, 0.0); }
// Odometry of a driver started at `zero` (its frame: where the robot was then).
Pose2 odometry_at(int64_t utime, int64_t zero = kT0)
{
  return Pose2(kOdometryScale * kSpeed * static_cast<double>(utime - zero) * 1e-6, 0.0, 0.0);
}

struct Fixture
{
  testing::TwoRoomWorld world = testing::two_room_world();
  LocalizerNodeOptions options = shipped_options();
  testing::FakeBusNode fake{"localizer"};
  std::unique_ptr<LocalizerNode> node;
  int64_t t = kT0;            // newest odometry sample
  int64_t seq = 0;
  int64_t odometry_zero = kT0;   // when the base driver started
  int64_t scan_id = 0;

  explicit Fixture(LocalizerFiles files = {}) { node = std::make_unique<LocalizerNode>(*fake.node, options, files); }

  void publish_map() { ASSERT_TRUE(bus::publish(*fake.bus, "RG_MAP", rgmap::to_msg(world.map))); }

  void odometry(int64_t utime)
  {
    odometry_t m{};
    m.utime = utime;
    m.seq = ++seq;
    m.odom_from_base = msg::to_msg(odometry_at(utime, odometry_zero));
    m.v = kSpeed;
    m.status = odometry_t::STATUS_SIMULATED;
    ASSERT_TRUE(bus::publish(*fake.bus, "ODOMETRY", m));
  }

  void scan(int64_t utime)
  {
    const auto s = testing::cast_scan(world.walls, truth_at(utime), options.localizer.base_from_laser, utime, ++scan_id);
    ASSERT_TRUE(bus::publish(*fake.bus, "LASER_FRONT", msg::to_msg(s)));
  }

  // Drives for `seconds`: odometry at 50 Hz, a scan every 100 ms stamped 10 ms after an
  // odometry sample (so it waits for the next one) or, every other time, 10 ms before one.
  void drive(double seconds)
  {
    const int ticks = static_cast<int>(std::lround(seconds * 50));
    for (int i = 0; i < ticks; ++i) {
      t += 20'000;
      odometry(t);
      if (i % 5 == 0) scan(scan_id % 2 == 0 ? t + 10'000 : t - 10'000);
    }
  }

  void request(const localize_request_t& m) { ASSERT_TRUE(bus::publish(*fake.bus, "LOCALIZE_REQUEST", m)); }

  std::vector<region_pose_t> poses() const { return testing::decoded<region_pose_t>(*fake.bus, "POSE"); }
  heartbeat_t heartbeat()
  {
    fake.node->publish_heartbeat();
    return testing::decoded<heartbeat_t>(*fake.bus, "HEARTBEAT").back();
  }
  int64_t drops_on(const std::string& channel) const { return fake.node->drops().on_channel(channel); }
};

localize_request_t pose_request(int64_t region, const std::string& name, const Pose2& pose, double sigma_xy = 0, double sigma_theta = 0)
{
  localize_request_t m{};
  m.utime = kT0;
  m.mode = localize_request_t::MODE_POSE;
  m.region_id = region;
  m.region_name = name;
  m.region_from_base = msg::to_msg(pose);
  m.sigma_xy = sigma_xy;
  m.sigma_theta = sigma_theta;
  return m;
}

void expect_near_truth(const region_pose_t& p, double xy = 0.1, double theta = 0.05)
{
  const Pose2 truth = truth_at(p.utime);
  const Pose2 est = msg::to_pose2(p.map_from_base);
  EXPECT_LT((est.translation() - truth.translation()).norm(), xy)
      << "estimate (" << est.x() << ", " << est.y() << ") truth (" << truth.x() << ", " << truth.y() << ") at scan " << p.scan_id;
  EXPECT_LT(std::fabs(geometry::normalize_angle(est.theta() - truth.theta())), theta) << "at scan " << p.scan_id;
}

TEST(LocalizerNode, PoseRequestThenTracksThroughTheDoor)
{
  Fixture f;
  EXPECT_EQ(f.node->localizer().mode(), Mode::kNoMap);
  f.publish_map();
  EXPECT_EQ(f.node->localizer().mode(), Mode::kUnknown);
  f.odometry(kT0);
  // Told the robot is near (1, 1.5) in room_a, 8 cm and 3 deg off.
  f.request(pose_request(f.world.room_a, "", Pose2(1.06, 1.45, 0.05), 0.15, 0.1));
  EXPECT_EQ(f.node->localizer().mode(), Mode::kTracking);
  f.drive(1.0);
  auto poses = f.poses();
  ASSERT_FALSE(poses.empty());
  EXPECT_EQ(poses.back().region_id, f.world.room_a);
  expect_near_truth(poses.back());
  // Through the door into room_b: 5 m more, ending 1.5 m past the door.
  f.drive(10.0);
  poses = f.poses();
  ASSERT_GT(poses.size(), 40u);   // an update per 0.1 m of odometry
  const auto& last = poses.back();
  EXPECT_EQ(last.region_id, f.world.room_b);
  expect_near_truth(last);
  const Pose2 in_b = Pose2(4, 0, 0).inverse() * truth_at(last.utime);
  EXPECT_LT((msg::to_pose2(last.region_from_base).translation() - in_b.translation()).norm(), 0.1);
  EXPECT_GT(last.confidence, 0.3f);
  EXPECT_NEAR(last.odom_from_base.x, odometry_at(last.utime).x(), 1e-9);
  EXPECT_GT(last.covariance[0], 0.0);
  EXPECT_NEAR(last.covariance[1], last.covariance[3], 1e-12);   // symmetric, row-major
  // Every estimate on the way, also at the door, where room_a's line map leaves the beams
  // through it unexplained and recovery candidates come from room_b too.
  for (const auto& p : poses) expect_near_truth(p, 0.15, 0.08);
  const auto passed = testing::decoded<gateway_passed_t>(*f.fake.bus, "LOCALIZER_GATEWAY_PASSED");
  ASSERT_EQ(passed.size(), 1u);
  EXPECT_EQ(passed[0].gateway_id, f.world.door);
  EXPECT_EQ(passed[0].from_region, f.world.room_a);
  EXPECT_EQ(passed[0].to_region, f.world.room_b);
  EXPECT_GE(passed[0].distance_past, f.options.localizer.gateway_passed_distance);
  EXPECT_EQ(f.node->localizer().mode(), Mode::kTracking);
  EXPECT_EQ(f.drops_on("LASER_FRONT"), 0);
  EXPECT_EQ(f.fake.node->drops().total(), 0);
  const auto hb = f.heartbeat();
  EXPECT_EQ(hb.state, heartbeat_t::STATE_RUNNING) << hb.status;
  EXPECT_NE(hb.status.find("tracking: "), std::string::npos) << hb.status;
  EXPECT_NE(hb.status.find(" particles, confidence "), std::string::npos) << hb.status;
  EXPECT_NE(hb.status.find(", 0 kidnaps, region 2"), std::string::npos) << hb.status;
}

TEST(LocalizerNode, RequestByNameAndGlobal)
{
  Fixture f;
  f.publish_map();
  f.odometry(kT0);
  f.request(pose_request(0, "room_a", Pose2(1.0, 1.5, 0.0)));
  EXPECT_EQ(f.node->localizer().mode(), Mode::kTracking);
  EXPECT_EQ(f.node->localizer().estimate().region, f.world.room_a);
  localize_request_t global{};
  global.utime = kT0;
  global.mode = localize_request_t::MODE_GLOBAL;
  f.request(global);
  EXPECT_EQ(f.node->localizer().mode(), Mode::kUnknown);
  EXPECT_FALSE(f.node->localizer().estimate().valid);
  EXPECT_EQ(f.fake.node->drops().total(), 0);
}

TEST(LocalizerNode, HostileRequestsAreDroppedAndCounted)
{
  Fixture f;
  f.publish_map();
  f.odometry(kT0);
  // Unknown region, by id and by name: decoded, then refused by the node.
  f.request(pose_request(99, "", Pose2(1, 1.5, 0)));
  f.request(pose_request(0, "kitchen", Pose2(1, 1.5, 0)));
  EXPECT_EQ(f.drops_on("LOCALIZE_REQUEST"), 2);
  // Refused before decoding: NaN in the pose (wire check), neither id nor name, a negative
  // spread (semantic checks), an unknown mode (enum check). Sent as raw bytes, since
  // bus::publish refuses to encode them.
  const auto raw = [&](localize_request_t m) {
    std::vector<uint8_t> buf(static_cast<size_t>(m.getEncodedSize()));
    ASSERT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
    ASSERT_TRUE(f.fake.bus->publish("LOCALIZE_REQUEST", buf.data(), buf.size()));
  };
  raw(pose_request(f.world.room_a, "", Pose2(std::numeric_limits<double>::quiet_NaN(), 1.5, 0)));
  auto m = pose_request(f.world.room_a, "", Pose2(1, 1.5, 0));
  m.region_from_base.theta = std::numeric_limits<double>::infinity();
  raw(m);
  raw(pose_request(0, "", Pose2(1, 1.5, 0)));
  raw(pose_request(f.world.room_a, "", Pose2(1, 1.5, 0), -0.1));
  m = pose_request(f.world.room_a, "", Pose2(1, 1.5, 0));
  m.mode = 7;
  raw(m);
  const uint8_t garbage[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  f.fake.bus->publish("LOCALIZE_REQUEST", garbage, sizeof garbage);
  EXPECT_EQ(f.drops_on("LOCALIZE_REQUEST"), 8);
  // None of them moved the filter: still waiting for its first scan to localize globally.
  EXPECT_EQ(f.node->localizer().mode(), Mode::kUnknown);
  const auto hb = f.heartbeat();
  EXPECT_EQ(hb.state, heartbeat_t::STATE_DEGRADED);
  EXPECT_EQ(hb.messages_dropped, 8);
  EXPECT_NE(hb.status.find("pose unknown: 0 particles"), std::string::npos) << hb.status;
  EXPECT_NE(hb.status.find("no scan used yet"), std::string::npos) << hb.status;
  // A pose request before any map is dropped too.
  Fixture empty;
  empty.request(pose_request(1, "", Pose2(1, 1.5, 0)));
  EXPECT_EQ(empty.drops_on("LOCALIZE_REQUEST"), 1);
  EXPECT_EQ(empty.node->localizer().mode(), Mode::kNoMap);
}

TEST(LocalizerNode, ScansWithoutOdometryAroundThemAreDropped)
{
  Fixture f;
  f.publish_map();
  f.scan(kT0 - 50'000);                    // no odometry yet
  EXPECT_EQ(f.drops_on("LASER_FRONT"), 1);
  f.odometry(kT0);
  f.scan(kT0 + 600'000);                   // the newest odometry is 0.6 s older (max_scan_age_s 0.5)
  EXPECT_EQ(f.drops_on("LASER_FRONT"), 2);
  f.scan(kT0 + 100'000);                   // waits for the odometry after it ...
  EXPECT_EQ(f.drops_on("LASER_FRONT"), 2);
  f.odometry(kT0 + 900'000);               // ... which comes 0.8 s later: too far
  EXPECT_EQ(f.drops_on("LASER_FRONT"), 3);
  f.scan(kT0 + 100'000);                   // not newer than the last scan
  EXPECT_EQ(f.drops_on("LASER_FRONT"), 4);
  f.scan(kT0 + 880'000);                   // between two samples 0.9 s apart
  EXPECT_EQ(f.drops_on("LASER_FRONT"), 5);
  // Odometry that goes back in time is dropped; a scan bracketed closely is used.
  f.t = kT0 + 900'000;
  f.odometry(kT0 + 800'000);
  EXPECT_EQ(f.drops_on("ODOMETRY"), 1);
  f.odometry(kT0 + 920'000);
  f.scan(kT0 + 910'000);
  EXPECT_EQ(f.drops_on("LASER_FRONT"), 5);
  EXPECT_EQ(f.node->localizer().stats().scans, 1);
  // Stamps that would overflow the time arithmetic.
  f.scan(-5);
  f.scan(std::numeric_limits<int64_t>::max());
  EXPECT_EQ(f.drops_on("LASER_FRONT"), 7);
  for (const int64_t utime : {std::numeric_limits<int64_t>::max(), std::numeric_limits<int64_t>::min()}) {
    odometry_t m{};
    m.utime = utime;
    m.seq = ++f.seq;
    ASSERT_TRUE(bus::publish(*f.fake.bus, "ODOMETRY", m));
  }
  EXPECT_EQ(f.drops_on("ODOMETRY"), 3);
  EXPECT_NE(f.node->localizer().mode(), Mode::kUnknown);   // the first scan started global localization
}

TEST(LocalizerNode, OdometryThatBreaksItsSequenceOrTimeIsUsedOnlyWhenTheNextSampleContinuesIt)
{
  Fixture f;
  f.publish_map();
  f.odometry(kT0);
  f.request(pose_request(f.world.room_a, "", Pose2(1.0, 1.5, 0.0)));
  f.drive(1.0);
  const auto corrupted = [&](int64_t seq, int64_t utime) {
    odometry_t m{};
    m.utime = utime;
    m.seq = seq;
    m.odom_from_base = msg::to_msg(Pose2(50, -3, 1));
    m.status = odometry_t::STATUS_SIMULATED;
    ASSERT_TRUE(bus::publish(*f.fake.bus, "ODOMETRY", m));
  };
  // A stray sample 100 s in the future: not continued by the next one, so it is dropped and
  // the odometry after it is used as before.
  corrupted(f.seq + 1, f.t + 100'000'000);
  EXPECT_EQ(f.drops_on("ODOMETRY"), 0);
  f.drive(0.5);
  EXPECT_EQ(f.drops_on("ODOMETRY"), 1);
  // A sample whose sequence went back, but the next one continues the old sequence.
  corrupted(f.seq - 2, f.t + 10'000);
  f.drive(0.5);
  EXPECT_EQ(f.drops_on("ODOMETRY"), 2);
  auto poses = f.poses();
  ASSERT_FALSE(poses.empty());
  expect_near_truth(poses.back());
  // The base driver really restarts: a new sequence and a new odometry frame, confirmed by its
  // second sample; the filter carries on from its estimate in the new frame.
  f.seq = 0;
  f.odometry_zero = f.t;
  const size_t before = f.poses().size();
  f.drive(2.0);
  EXPECT_EQ(f.drops_on("ODOMETRY"), 2);
  poses = f.poses();
  ASSERT_GT(poses.size(), before + 5);
  EXPECT_NEAR(poses.back().odom_from_base.x, odometry_at(poses.back().utime, f.odometry_zero).x(), 1e-9);
  expect_near_truth(poses.back());
  EXPECT_EQ(f.node->localizer().mode(), Mode::kTracking);
  EXPECT_LE(f.drops_on("LASER_FRONT"), 1);   // at most the scan that waited across the restart
}

// Under load the base driver repeats its last sample (same stamp, newer sequence number) when the
// drives' next one is late: no drop, also not after a pause in the time that holds a sample.
TEST(LocalizerNode, TheSameOdometrySampleRepeatedIsNoDrop)
{
  Fixture f;
  f.publish_map();
  f.odometry(kT0);
  f.request(pose_request(f.world.room_a, "", Pose2(1.0, 1.5, 0.0)));
  f.drive(1.0);
  f.odometry(f.t);
  f.odometry(f.t);
  f.drive(0.5);
  EXPECT_EQ(f.drops_on("ODOMETRY"), 0);
  f.t += 1'500'000;   // a pause longer than max_odometry_gap_s: the sample after it is held ...
  f.odometry(f.t);
  f.odometry(f.t);    // ... and repeated before the next one continues it
  f.drive(0.5);
  EXPECT_EQ(f.drops_on("ODOMETRY"), 0);
  const auto poses = f.poses();
  ASSERT_FALSE(poses.empty());
  EXPECT_EQ(f.node->localizer().mode(), Mode::kTracking);
}

TEST(LocalizerNode, SavesTheEstimateAndResumesFromItAfterARestart)
{
  testing::TempDir dir("localizer_node");
  const auto world = testing::two_room_world();
  testing::write_rgmap_json(world.map, dir.file("map"));
  LocalizerFiles files{dir.file("map"), dir.file("state/estimate")};
  int64_t t_end = 0;
  {
    Fixture f(files);
    EXPECT_EQ(f.node->localizer().mode(), Mode::kUnknown);   // the saved map is loaded; no saved estimate yet
    EXPECT_FALSE(f.node->resumed_from().has_value());
    f.odometry(kT0);
    f.request(pose_request(f.world.room_a, "", Pose2(1.05, 1.45, 0.04), 0.15, 0.1));
    f.drive(3.0);
    EXPECT_GE(f.node->estimates_saved(), 2);   // every persist_period_s (1 s) of scan time while converged
    const auto saved = load_estimate(files.state_file);
    ASSERT_TRUE(saved.has_value());
    EXPECT_EQ(saved->region, f.world.room_a);
    EXPECT_LT((saved->map_from_base.translation() - truth_at(saved->utime).translation()).norm(), 0.1);
    EXPECT_EQ(saved->map_version, f.world.map.version);
    t_end = f.t;
  }
  // The node's stop saved the newest estimate.
  const auto last = load_estimate(files.state_file);
  ASSERT_TRUE(last.has_value());
  EXPECT_GT(last->utime, t_end - 300'000);

  Fixture g(files);
  ASSERT_TRUE(g.node->resumed_from().has_value());
  EXPECT_EQ(g.node->resumed_from()->utime, last->utime);
  EXPECT_EQ(g.node->localizer().mode(), Mode::kTracking);
  EXPECT_LT((g.node->localizer().estimate().map_from_base.translation() - last->map_from_base.translation()).norm(), 1e-9);
  // The robot drives on (same odometry); POSE follows it from the resumed estimate.
  g.t = t_end;
  g.scan_id = 1000;
  g.odometry(g.t);
  g.drive(2.0);
  const auto poses = g.poses();
  ASSERT_FALSE(poses.empty());
  expect_near_truth(poses.back());
  EXPECT_EQ(g.node->localizer().mode(), Mode::kTracking);
  EXPECT_EQ(g.fake.node->drops().total(), 0);
}

TEST(LocalizerNode, SavedEstimateIsResumedWhenTheMapArrivesOnTheBus)
{
  testing::TempDir dir("localizer_node");
  const auto world = testing::two_room_world();
  SavedEstimate s;
  s.utime = kT0;
  s.region = world.room_b;
  s.region_from_base = Pose2(1.0, 1.5, 0.0);
  s.map_from_base = Pose2(5.0, 1.5, 0.0);
  s.map_version = 1;
  save_estimate(dir.file("estimate"), s);
  Fixture f(LocalizerFiles{"", dir.file("estimate")});
  EXPECT_EQ(f.node->localizer().mode(), Mode::kNoMap);
  EXPECT_FALSE(f.node->resumed_from().has_value());
  f.publish_map();
  ASSERT_TRUE(f.node->resumed_from().has_value());
  EXPECT_EQ(f.node->localizer().mode(), Mode::kTracking);
  EXPECT_EQ(f.node->localizer().estimate().region, world.room_b);
  // The same map version again changes nothing.
  f.publish_map();
  EXPECT_EQ(f.node->localizer().mode(), Mode::kTracking);
}

TEST(LocalizerNode, ADamagedSavedMapOrEstimateIsRefusedOrIgnored)
{
  testing::TempDir dir("localizer_node");
  {
    std::ofstream(dir.file("rgmap.json")) << "not a checkpoint";
    std::ofstream(dir.file("estimate")) << "garbage";
  }
  try {
    Fixture f(LocalizerFiles{dir.path(), ""});
    FAIL() << "a damaged map was loaded";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(dir.file("rgmap.json")), std::string::npos) << e.what();
  }
  EXPECT_THROW({ Fixture missing(LocalizerFiles{dir.file("missing"), ""}); }, config::ConfigError);
  // A damaged estimate is no estimate: global localization.
  testing::write_rgmap_json(testing::two_room_world().map, dir.file("good"));
  Fixture f(LocalizerFiles{dir.file("good"), dir.file("estimate")});
  EXPECT_FALSE(f.node->resumed_from().has_value());
  EXPECT_EQ(f.node->localizer().mode(), Mode::kUnknown);
}

// Issue 35: a --map file of random bytes, an empty one or one cut off mid-content refuses the
// start naming the file; a saved estimate of the same is not used, moved aside as found
// (.damaged) and the localizer starts unlocalized.
TEST(LocalizerNode, BadMapOrEstimateFilesOfRandomBytesEmptyOrCutOff)
{
  testing::TempDir dir("localizer_bad");
  testing::write_rgmap_json(testing::two_room_world().map, dir.file("good"));
  SavedEstimate s;
  s.utime = 1;
  s.region = testing::two_room_world().room_a;
  save_estimate(dir.file("estimate"), s);
  const auto maps = testing::write_bad_files(dir.path(), "rgmap.json", testing::read_file(dir.file("good/rgmap.json")));
  const auto estimates = testing::write_bad_files(dir.path(), "estimate", testing::read_file(dir.file("estimate")));
  for (size_t k = 0; k < maps.size(); ++k) {
    SCOPED_TRACE(maps[k].kind);
    try {
      Fixture f(LocalizerFiles{maps[k].path, ""});
      ADD_FAILURE() << maps[k].path << " was loaded as a map";
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(maps[k].path), std::string::npos) << e.what();
    }
    const std::string bytes = testing::read_file(estimates[k].path);
    Fixture f(LocalizerFiles{dir.file("good"), estimates[k].path});
    EXPECT_FALSE(f.node->resumed_from().has_value());
    EXPECT_EQ(f.node->localizer().mode(), Mode::kUnknown);
    EXPECT_EQ(testing::read_file(estimates[k].path + ".damaged"), bytes);
  }
}

TEST(LocalizerProcess, ShippedConfigPassesCheckConfigAndAMisspeltKeyIsRefused)
{
  testing::TempDir dir("localizer_config");
  testing::ChildOptions o;
  o.stderr_path = dir.file("stderr");
  auto status = testing::run_to_completion({RGNAV_LOCALIZER_BIN, "--config", RGNAV_SOURCE_DIR "/config/localizer.yaml",
                                            "--check-config"},
                                           std::chrono::seconds(30), o);
  EXPECT_TRUE(status.clean()) << status.describe() << testing::read_file(dir.file("stderr"));
  {
    std::ifstream in(RGNAV_SOURCE_DIR "/config/localizer.yaml");
    std::ofstream out(dir.file("localizer.yaml"));
    std::string line;
    while (std::getline(in, line)) {
      const auto at = line.find("kidnap_after_s");
      if (at != std::string::npos) line.replace(at, 14, "kidnap_afer_s");
      out << line << "\n";
    }
  }
  status = testing::run_to_completion({RGNAV_LOCALIZER_BIN, "--config", dir.file("localizer.yaml"), "--check-config"},
                                      std::chrono::seconds(30), o);
  EXPECT_TRUE(status.exited && status.code == 2) << status.describe();
  const std::string err = testing::read_file(dir.file("stderr"));
  EXPECT_NE(err.find(dir.file("localizer.yaml")), std::string::npos) << err;
  EXPECT_NE(err.find("recovery.kidnap_afer_s"), std::string::npos) << err;
}

TEST(LocalizerProcess, OperatorToolSendsValidRequestsOnlyInProcessMemq)
{
  // memq:// keeps the request inside the tool: only what it accepts and refuses is checked here.
  const auto run = [](std::vector<std::string> args) {
    args.insert(args.begin(), RGNAV_LOCALIZE_BIN);
    args.insert(args.end(), {"--lcm-url", "memq://"});
    return testing::run_to_completion(args, std::chrono::seconds(30));
  };
  EXPECT_TRUE(run({"--region", "room_a", "--pose", "1", "1.5", "90"}).clean());
  EXPECT_TRUE(run({"--region", "2", "--pose", "1", "1.5", "-45", "--sigma-xy", "0.3", "--sigma-theta", "20"}).clean());
  EXPECT_TRUE(run({"--global"}).clean());
  for (const auto& bad : std::vector<std::vector<std::string>>{{}, {"--region", "room_a"}, {"--pose", "1", "2", "3"},
                                                               {"--region", "room_a", "--pose", "1", "nan", "0"},
                                                               {"--global", "--region", "room_a", "--pose", "1", "2", "3"},
                                                               {"--region", "room_a", "--pose", "1", "2", "3", "--sigma-xy", "-1"}}) {
    const auto status = run(bad);
    EXPECT_TRUE(status.exited && status.code != 0) << status.describe() << " for " << ::testing::PrintToString(bad);
  }
}

}  // namespace
}  // namespace rgnav::localizer
