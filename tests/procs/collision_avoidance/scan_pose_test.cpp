// A scan is placed in the odometry frame with the pose at its own stamp, between the odometry
// messages around it, not with the newest pose: scans come at 75 Hz, odometry at 50 Hz, and
// odometry newer than a scan often arrives first. Placed with the newest pose, the scans of a
// turn on the spot put a wall a few degrees off from one scan to the next: pieces of it moved,
// the people tracker followed them as people walking, and the robot yielded to nobody at a
// hallway's mouth.
#include <gtest/gtest.h>

#include <cmath>

#include "collision_avoidance/collision_avoidance.h"
#include "scan_fixture.h"

namespace rgnav::collision_avoidance {
namespace {

TEST(ScanPose, AScanTakenDuringATurnLiesWhereItsWallIs)
{
  CaOptions o;
  CollisionAvoidance ca(o);
  const std::vector<testing::Wall> wall = {{{3.0, -3.0}, {3.0, 3.0}}};
  // Turning on the spot at 2 rad/s: heading 0 at 1.00 s, 0.1 at 1.05 s; the scan was taken at
  // 1.00 s (heading 0) and arrives after both odometry messages.
  const Pose2 then(0.0, 0.0, 0.0), now(0.0, 0.0, 0.1);
  ca.on_odometry(time::from_utime(1'000'000), then, 0.0);
  ca.on_odometry(time::from_utime(1'050'000), now, 0.0);
  ca.on_scan(time::from_utime(1'000'000), testing::cast(then * o.base_from_laser, wall), 8.0);
  ca.update(time::from_utime(1'050'000));
  ASSERT_FALSE(ca.map().points().empty());
  double worst = 0.0;
  for (const auto& p : ca.map().points()) worst = std::max(worst, std::fabs(p.x() - 3.0));
  EXPECT_LT(worst, 0.02) << "the wall's points lie up to " << worst << " m off it";

  // A scan newer than every odometry message: the newest pose (nothing later to go by).
  CollisionAvoidance late(o);
  late.on_odometry(time::from_utime(1'000'000), now, 0.0);
  late.on_scan(time::from_utime(1'020'000), testing::cast(now * o.base_from_laser, wall), 8.0);
  late.update(time::from_utime(1'020'000));
  ASSERT_FALSE(late.map().points().empty());
  worst = 0.0;
  for (const auto& p : late.map().points()) worst = std::max(worst, std::fabs(p.x() - 3.0));
  EXPECT_LT(worst, 0.02);
}

// The base driver repeats its last sample's stamp when no new one came (a loaded host delays the
// drives): the history stays, so a scan between two samples still gets its own pose.
TEST(ScanPose, TheSameOdometrySampleRepeatedKeepsTheHistory)
{
  CaOptions o;
  CollisionAvoidance ca(o);
  const std::vector<testing::Wall> wall = {{{3.0, -3.0}, {3.0, 3.0}}};
  const Pose2 then(0.0, 0.0, 0.0), now(0.0, 0.0, 0.1);
  ca.on_odometry(time::from_utime(1'000'000), then, 0.0);
  ca.on_odometry(time::from_utime(1'050'000), now, 0.0);
  ca.on_odometry(time::from_utime(1'050'000), now, 0.0);
  ca.on_scan(time::from_utime(1'000'000), testing::cast(then * o.base_from_laser, wall), 8.0);
  ca.update(time::from_utime(1'050'000));
  ASSERT_FALSE(ca.map().points().empty());
  double worst = 0.0;
  for (const auto& p : ca.map().points()) worst = std::max(worst, std::fabs(p.x() - 3.0));
  EXPECT_LT(worst, 0.02) << "the wall's points lie up to " << worst << " m off it";
}

}  // namespace
}  // namespace rgnav::collision_avoidance
