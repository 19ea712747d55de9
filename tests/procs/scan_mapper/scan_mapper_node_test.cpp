// The node adapter over the FakeBus: messages in, ALIGNED_SCAN / SLAM_POSE out, republished
// corrections after a loop closure, persistence across a restart, invalid input dropped.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "bus/fake_bus.h"
#include "bus/typed.h"
#include "scan_mapper/scan_mapper_conversions.h"
#include "scan_mapper/scan_mapper_node.h"
#include "node_harness.h"

namespace sm = rgnav::scan_mapper;
namespace fs = std::filesystem;
using rgnav::aligned_scan_t;
using rgnav::laser_scan_t;
using rgnav::odometry_t;
using rgnav::slam_pose_t;

using Harness = sm::testing::NodeHarness;
using sm::testing::drive;

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
  h.bus->publish("LASER_FRONT", junk.data(), junk.size());
  EXPECT_TRUE(h.published<aligned_scan_t>("ALIGNED_SCAN").empty());
  EXPECT_GE(h.node->drops().total(), 1);
}

TEST(ScanMapperNode, ResumesFromPersistedStateAfterRestart)
{
  const auto dir = fs::temp_directory_path() / ("rgnav_sm_node_" + std::to_string(::getpid()));
  sm::PersistenceOptions p;
  p.state_file = (dir / "state.bin").string();
  p.snapshot_every_records = 5;
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
