// A scan is placed in the odometry frame with the pose at its own stamp, between the odometry
// messages around it, not with the newest pose: scans come at 75 Hz, odometry at 50 Hz, and
// odometry newer than a scan often arrives first. Placed with the newest pose, the scans of a
// turn on the spot put a wall a few degrees off from one scan to the next: pieces of it moved,
// the people tracker followed them as people walking, and the robot yielded to nobody at a
// hallway's mouth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "collision_avoidance/collision_avoidance.h"
#include "scan_fixture.h"

namespace rgnav::collision_avoidance {
namespace {

const std::vector<testing::Wall> kWall = {{{3.0, -3.0}, {3.0, 3.0}}};

// How far the wall's points lie from it once a scan taken at `scan_us` from `taken_from` is in
// the map, after the odometry messages `odometry` (stamp, pose).
double worst_wall_error(const std::vector<std::pair<int64_t, Pose2>>& odometry, int64_t scan_us, const Pose2& taken_from)
{
  CaOptions o;
  CollisionAvoidance ca(o);
  for (const auto& [us, pose] : odometry) ca.on_odometry(time::from_utime(us), pose, 0.0);
  ca.on_scan(time::from_utime(scan_us), testing::cast(taken_from * o.base_from_laser, kWall), 8.0);
  ca.update(time::from_utime(std::max(scan_us, odometry.back().first)));
  if (ca.map().points().empty()) return 1e9;
  double worst = 0.0;
  for (const auto& p : ca.map().points()) worst = std::max(worst, std::fabs(p.x() - 3.0));
  return worst;
}

// Turning on the spot at 2 rad/s: heading 0 at 1.00 s, 0.1 at 1.05 s.
const Pose2 kThen(0.0, 0.0, 0.0), kNow(0.0, 0.0, 0.1);

TEST(ScanPose, AScanTakenDuringATurnLiesWhereItsWallIs)
{
  // The scan was taken at 1.00 s (heading 0) and arrives after both odometry messages.
  EXPECT_LT(worst_wall_error({{1'000'000, kThen}, {1'050'000, kNow}}, 1'000'000, kThen), 0.02);
  // A scan newer than every odometry message: the newest pose (nothing later to go by).
  EXPECT_LT(worst_wall_error({{1'000'000, kNow}}, 1'020'000, kNow), 0.02);
}

// The base driver repeats its last sample's stamp when no new one came (a loaded host delays the
// drives): the history stays, so a scan between two samples still gets its own pose.
TEST(ScanPose, TheSameOdometrySampleRepeatedKeepsTheHistory)
{
  EXPECT_LT(worst_wall_error({{1'000'000, kThen}, {1'050'000, kNow}, {1'050'000, kNow}}, 1'000'000, kThen), 0.02);
}

}  // namespace
}  // namespace rgnav::collision_avoidance
