// The order in which the vision takes its inputs (vision/frame_sync.h), shared by the process and
// the lock-step benches: a frame waits for odometry past it and gets the pose interpolated at its
// capture; only the newest frame waits; a frame without odometry close on both sides is dropped;
// scans are fused at most every laser_period; odometry going back starts the map afresh.
#include "vision/frame_sync.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "synthetic_stereo.h"

namespace rgnav::vision {
namespace {

using geometry::Pose2;

constexpr int64_t kT0 = 1'700'000'000'000'000;
const cv::Size kSize(320, 240);

struct Harness
{
  VisionPipeline pipeline{ideal_rig(kSize, 250.0, 0.12), [] {
                            VisionOptions o;
                            o.rectangles.enabled = false;
                            o.disparity.downscale = 1;
                            return o;
                          }()};
  std::vector<std::pair<int64_t, Pose2>> processed;   // frame time, pose it was given
  std::vector<std::string> frame_drops, scan_drops;
  FrameSync sync{pipeline, FrameSyncOptions{0.2, 0.1, Pose2(0.12, 0, 0)},
                 {[this](const StereoFrame& f, const FrameResult&) { processed.emplace_back(f.utime, f.odom_from_base); },
                  [this](const std::string& why) { frame_drops.push_back(why); },
                  [this](const std::string& why) { scan_drops.push_back(why); },
                  {}}};

  StereoFrame frame(int64_t utime) const
  {
    const auto p = synthetic::plane_pair(kSize, 20, 3);
    StereoFrame f;
    f.utime = utime;
    f.left = p.left;
    f.right = p.right;
    return f;
  }
};

sensors::LaserScan scan(int64_t utime)
{
  sensors::LaserScan s;
  s.utime = utime;
  s.angle_min = -M_PI / 2;
  s.angle_increment = M_PI / 180;
  s.range_min = 0.01;
  s.range_max = 8.0;
  s.ranges.assign(181, 2.0f);
  return s;
}

TEST(FrameSync, AFrameWaitsForTheOdometryPastItAndGetsTheInterpolatedPose)
{
  Harness h;
  h.sync.on_odometry(kT0, 1, Pose2(0, 0, 0));
  h.sync.on_frame(h.frame(kT0 + 10'000));
  EXPECT_TRUE(h.processed.empty());   // no odometry after the capture yet
  h.sync.on_odometry(kT0 + 20'000, 2, Pose2(0.2, 0, 0));
  ASSERT_EQ(h.processed.size(), 1u);
  EXPECT_EQ(h.processed[0].first, kT0 + 10'000);
  EXPECT_NEAR(h.processed[0].second.x(), 0.1, 1e-9);
  EXPECT_EQ(h.sync.frames_processed(), 1);
}

TEST(FrameSync, OnlyTheNewestFrameWaits)
{
  Harness h;
  h.sync.on_odometry(kT0, 1, Pose2());
  h.sync.on_frame(h.frame(kT0 + 10'000));
  h.sync.on_frame(h.frame(kT0 + 15'000));
  h.sync.on_odometry(kT0 + 20'000, 2, Pose2());
  ASSERT_EQ(h.processed.size(), 1u);
  EXPECT_EQ(h.processed[0].first, kT0 + 15'000);
  EXPECT_EQ(h.sync.frames_superseded(), 1);
}

TEST(FrameSync, AFrameWithoutOdometryCloseOnBothSidesIsDropped)
{
  Harness h;
  h.sync.on_odometry(kT0, 1, Pose2());
  h.sync.on_frame(h.frame(kT0 + 10'000));
  h.sync.on_odometry(kT0 + 500'000, 2, Pose2());   // 0.5 s later: beyond max_pose_gap 0.2 s
  EXPECT_TRUE(h.processed.empty());
  ASSERT_EQ(h.frame_drops.size(), 1u);
  EXPECT_NE(h.frame_drops[0].find("max_pose_gap"), std::string::npos);
}

TEST(FrameSync, ScansAreFusedAtMostEveryLaserPeriod)
{
  Harness h;
  // 2 s of odometry at 50 Hz and scans at 75 Hz: about 20 fused at 0.1 s, not 150.
  int64_t next_scan = kT0;
  for (int i = 0; i <= 100; ++i) {
    const int64_t t = kT0 + i * 20'000;
    while (next_scan <= t) {
      h.sync.on_laser(scan(next_scan));
      next_scan += 13'333;
    }
    h.sync.on_odometry(t, i + 1, Pose2(0.01 * i, 0, 0));
  }
  EXPECT_GE(h.sync.laser_scans_fused(), 16);
  EXPECT_LE(h.sync.laser_scans_fused(), 21);
  EXPECT_TRUE(h.scan_drops.empty());
}

TEST(FrameSync, OdometryGoingBackStartsTheMapAfresh)
{
  Harness h;
  h.sync.on_odometry(kT0, 1, Pose2());
  for (int i = 0; i < 3; ++i) h.sync.on_laser(scan(kT0 + i * 100'000));
  h.sync.on_odometry(kT0 + 300'000, 2, Pose2());
  ASSERT_GT(h.pipeline.map().leaf_count(), 0u);
  EXPECT_FALSE(h.sync.on_odometry(kT0 + 320'000, 3, Pose2()));
  EXPECT_TRUE(h.sync.on_odometry(kT0 + 100'000, 1, Pose2()));   // a restarted base driver
  EXPECT_EQ(h.sync.map_resets(), 1);
  EXPECT_EQ(h.pipeline.map().leaf_count(), 0u);
}

// The base driver publishes at its own rate; when the drives' samples are late (a loaded host) a
// message repeats the last sample's stamp under a new sequence number. The map stays.
TEST(FrameSync, TheSameOdometrySampleRepeatedKeepsTheMap)
{
  Harness h;
  h.sync.on_odometry(kT0, 1, Pose2());
  for (int i = 0; i < 3; ++i) h.sync.on_laser(scan(kT0 + i * 100'000));
  h.sync.on_odometry(kT0 + 300'000, 2, Pose2());
  const auto leaves = h.pipeline.map().leaf_count();
  ASSERT_GT(leaves, 0u);
  EXPECT_FALSE(h.sync.on_odometry(kT0 + 300'000, 3, Pose2()));
  EXPECT_FALSE(h.sync.on_odometry(kT0 + 300'000, 4, Pose2()));
  EXPECT_EQ(h.sync.map_resets(), 0);
  EXPECT_EQ(h.pipeline.map().leaf_count(), leaves);
  EXPECT_TRUE(h.sync.on_odometry(kT0 + 300'000, 2, Pose2()));   // its sequence went back: a restart
  EXPECT_EQ(h.sync.map_resets(), 1);
}

}  // namespace
}  // namespace rgnav::vision
