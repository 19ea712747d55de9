// The node adapter over the FakeBus: messages in, ALIGNED_SCAN / SLAM_POSE out, republished
// corrections after a loop closure, persistence across a restart, invalid input dropped.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "bus/fake_bus.h"
#include "bus/typed.h"
#include "scan_mapper/scan_mapper_conversions.h"
#include "scan_mapper/scan_mapper_node.h"
#include "synthetic_world.h"

namespace sm = rgnav::scan_mapper;
namespace fs = std::filesystem;
using rgnav::aligned_scan_t;
using rgnav::laser_scan_t;
using rgnav::odometry_t;
using rgnav::slam_pose_t;

namespace {

struct Harness
{
  explicit Harness(const sm::PersistenceOptions& p)
  {
    auto bus = std::make_unique<rgnav::bus::FakeBus>();
    fake = bus.get();
    rgnav::runtime::NodeOptions no;
    no.name = "scan_mapper_test";
    node = std::make_unique<rgnav::runtime::Node>(no, std::move(bus));
    sm::ScanMapperOptions o;
    o.base_from_laser = sm::Pose2{};
    adapter = std::make_unique<sm::ScanMapperNode>(*node, o, sm::ScanMapperChannels{}, p);
  }
  template <class T>
  std::vector<T> published(const std::string& channel) const
  {
    std::vector<T> out;
    for (const auto& m : fake->published_on(channel)) {
      T msg;
      std::string why;
      EXPECT_TRUE(rgnav::bus::decode(m.data.data(), m.data.size(), &msg, &why)) << why;
      out.push_back(msg);
    }
    return out;
  }
  rgnav::bus::FakeBus* fake = nullptr;
  std::unique_ptr<rgnav::runtime::Node> node;
  std::unique_ptr<sm::ScanMapperNode> adapter;
};

// Out along the corridor and back: 0.05 m steps, scans every step.
void drive(Harness& h, int from, int to, int64_t seq0 = 0)
{
  const auto world = sm::testing::office_world();
  std::mt19937 rng(2);
  sm::testing::LaserModel m;
  m.noise_m = 0.01;
  for (int i = from; i < to; ++i) {
    const int leg = i % 300;
    const double s = leg < 150 ? leg * 0.05 : (300 - leg) * 0.05;
    const sm::Pose2 truth = leg < 150 ? sm::Pose2{1 + s, 0.5, 0} : sm::Pose2{1 + s, 0.5, M_PI};
    odometry_t o{};
    o.utime = 1'000'000 + i * 100'000;
    o.seq = seq0 + i + 1;
    o.odom_from_base = sm::to_message(sm::Pose2{truth.x * 1.01, truth.y, truth.theta});
    rgnav::bus::publish(h.node->bus(), "ODOMETRY", o);
    const auto scan = sm::testing::cast_scan(world, truth, m, &rng, i + 1, o.utime);
    rgnav::bus::publish(h.node->bus(), "LASER_FRONT", sm::to_message(scan, "laser_front"));
  }
}

}  // namespace

TEST(ScanMapperNode, PublishesAlignedScansAndPoses)
{
  Harness h(sm::PersistenceOptions{});
  drive(h, 0, 300);
  const auto aligned = h.published<aligned_scan_t>("ALIGNED_SCAN");
  const auto poses = h.published<slam_pose_t>("SLAM_POSE");
  ASSERT_GT(aligned.size(), 20u);
  EXPECT_FALSE(poses.empty());
  int first_publications = 0, republications = 0;
  for (const auto& a : aligned) {
    (a.revision == 0 ? first_publications : republications)++;
    EXPECT_EQ(a.scan.nranges, 181);
    EXPECT_EQ(a.base_from_laser.x, 0.0);
  }
  EXPECT_EQ(first_publications, static_cast<int>(h.adapter->mapper().nodes().size()));
  // Driving back along the corridor closes loops and republishes corrected scans.
  EXPECT_GE(h.adapter->mapper().stats().loop_closures, 1);
  EXPECT_GT(republications, 0);
  EXPECT_EQ(poses.back().scan_id, aligned.back().scan_id);
}

TEST(ScanMapperNode, InvalidMessagesAreDroppedNotFatal)
{
  Harness h(sm::PersistenceOptions{});
  laser_scan_t bad{};
  bad.scan_id = 0;  // never valid
  bad.nranges = 1;
  bad.ranges = {1.f};
  bad.angle_increment = 0.01f;
  bad.range_max = 10.f;
  const std::vector<uint8_t> junk = {1, 2, 3};
  h.fake->publish("LASER_FRONT", junk.data(), junk.size());
  EXPECT_TRUE(h.published<aligned_scan_t>("ALIGNED_SCAN").empty());
  EXPECT_GE(h.node->drops().total(), 1);
}

TEST(ScanMapperNode, ResumesFromPersistedStateAfterRestart)
{
  const auto dir = fs::temp_directory_path() / ("rgnav_sm_node_" + std::to_string(::getpid()));
  sm::PersistenceOptions p;
  p.state_file = (dir / "state.bin").string();
  p.save_every_scans = 5;
  size_t before = 0;
  {
    Harness h(p);
    drive(h, 0, 120);
    before = h.adapter->mapper().nodes().size();
  }  // destructor saves the rest
  ASSERT_TRUE(fs::exists(p.state_file));
  Harness h2(p);
  EXPECT_EQ(h2.adapter->mapper().nodes().size(), before);
  // The restarted base driver counts from 1 again with a new origin... here the same origin.
  drive(h2, 120, 200, -120);
  EXPECT_GT(h2.adapter->mapper().nodes().size(), before + 3);
  const auto aligned = h2.published<aligned_scan_t>("ALIGNED_SCAN");
  ASSERT_FALSE(aligned.empty());
  EXPECT_GT(aligned.front().scan_id, 120);  // continues, does not restart the map
  fs::remove_all(dir);
}
