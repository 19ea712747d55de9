// The way back along the robot's own track (own_track.h): a robot that drove into a pocket
// with less than the full clearance (the reactive fallback steers with half the safety
// margin) leaves it the way it came, with the clearance it had there; every other rule wants
// the full clearance, or 0.5 m more of it per metre, and kept it standing there for good.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "collision_avoidance/collision_avoidance.h"
#include "collision_avoidance/own_track.h"
#include "scan_fixture.h"

namespace rgnav::collision_avoidance {
namespace {

using testing::Wall;

// A room (x in [-3, 0]) with a dead-end pocket off its east side: x in [0, 1.5], 0.64 m wide
// (0.32 m to either side from its centre line: more than the robot's radius, less than radius
// plus safety margin), closed at its far end.
std::vector<Wall> room_with_pocket()
{
  std::vector<Wall> w;
  w.push_back({{-3.0, -2.0}, {0.0, -2.0}});
  w.push_back({{-3.0, 2.0}, {0.0, 2.0}});
  w.push_back({{-3.0, -2.0}, {-3.0, 2.0}});
  w.push_back({{0.0, -2.0}, {0.0, -0.32}});
  w.push_back({{0.0, 0.32}, {0.0, 2.0}});
  w.push_back({{0.0, -0.32}, {1.5, -0.32}});
  w.push_back({{0.0, 0.32}, {1.5, 0.32}});
  w.push_back({{1.5, -0.32}, {1.5, 0.32}});
  return w;
}

double distance_to_pocket_walls(const std::vector<Wall>& walls, const Eigen::Vector2d& p)
{
  double best = std::numeric_limits<double>::infinity();
  for (const auto& w : walls) {
    const Eigen::Vector2d ab = w.b - w.a;
    const double t = std::clamp((p - w.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (w.a + t * ab - p).norm());
  }
  return best;
}

// Collision avoidance with a simple drive: it follows the active trajectory's segments in
// turn (lines and arcs at their speed limit, at most 0.3 m/s; turns on the spot at 1 rad/s)
// and stops at its end. Scans from the ray caster, every 0.1 s.
struct PocketDrive
{
  explicit PocketDrive(const CaOptions& o) : options(o), ca(o) {}

  // Where the drive has the robot `t` seconds into `chain`, and the arc length done.
  static std::pair<Pose2, double> along(const trajectory::Chain& chain, double t, bool* done)
  {
    double s = 0.0;
    for (size_t i = 0; i < chain.size(); ++i) {
      const auto& seg = chain[i];
      const bool turn = seg.kind() == trajectory::Kind::kTurn;
      const double duration = turn ? std::fabs(seg.turn_angle()) : seg.length() / std::min(0.3, seg.v_max());
      if (t < duration) {
        const double f = t / duration;
        if (turn) {
          const Pose2 p = seg.start();
          return {Pose2(p.translation(), p.theta() + f * seg.turn_angle()), s};
        }
        return {seg.pose_at(f * seg.length()), s + f * seg.length()};
      }
      t -= duration;
      s += seg.length();
    }
    *done = true;
    return {chain.end(), s};
  }

  void step()
  {
    us += 100'000;
    const time::Time now = time::from_utime(us);
    bool done = true;
    double progress = 0.0;
    if (active && !active->chain.empty()) {
      done = false;
      const auto at = along(active->chain, time::to_seconds(now - active->stamp), &done);
      pose = at.first;
      progress = at.second;
      min_wall_distance = std::min(min_wall_distance, distance_to_pocket_walls(walls, pose.translation()));
    }
    ca.on_odometry(now, pose, done ? 0.0 : 0.15);
    ca.on_scan(now, testing::cast(pose * options.base_from_laser, walls), 8.0);
    if (active) ca.on_drive_feedback({active->id, done ? 2 : 1, progress, 0.0, done ? 0.0 : 0.15});
    if (auto out = ca.update(now)) {
      if (!active || out->id != active->id) active = out;
    }
  }

  CaOptions options;
  CollisionAvoidance ca;
  std::vector<Wall> walls = room_with_pocket();
  Pose2 pose;
  std::optional<trajectory::Trajectory> active;
  int64_t us = 1'000'000;
  double min_wall_distance = std::numeric_limits<double>::infinity();
};

// Into the pocket along its centre line (as the reactive fallback steered it there, with
// 0.32 m to either side), to x = 1.1, 0.4 m short of its end; the target lies beyond the
// pocket's far end. Then the robot is left to collision avoidance for `seconds`.
Pose2 stuck_in_pocket(PocketDrive* d, double seconds)
{
  Targets t;
  t.goal_id = 7;
  t.poses = {Pose2(2.5, 0.0, 0.0)};
  d->ca.set_targets(t);
  for (double x = -1.5; x <= 1.1 + 1e-9; x += 0.05) {
    d->us += 100'000;
    const time::Time now = time::from_utime(d->us);
    d->pose = Pose2(x, 0.0, 0.0);
    d->ca.on_odometry(now, d->pose, 0.5);
    d->ca.on_scan(now, testing::cast(d->pose * d->options.base_from_laser, d->walls), 8.0);
    d->ca.update(now);
  }
  d->min_wall_distance = std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(seconds * 10.0); ++i) d->step();
  return d->pose;
}

TEST(OwnTrack, LeavesAPocketItDroveIntoTheWayItCame)
{
  CaOptions o;
  ASSERT_TRUE(o.retrace_own_track);
  PocketDrive d(o);
  const Pose2 out = stuck_in_pocket(&d, 40.0);
  // Out in the room, past the pocket's mouth, with the full clearance.
  EXPECT_LT(out.x(), -0.2) << "at " << out.x() << ", " << out.y() << ": " << d.ca.status();
  EXPECT_GE(distance_to_pocket_walls(d.walls, out.translation()), o.planner.robot_radius + o.planner.safety_margin);
  // Never closer to the pocket's sides than the robot was on the way in (0.32 m), less noise.
  EXPECT_GE(d.min_wall_distance, 0.30);
}

// Without it the robot stands in the pocket (the failure this fixes).
TEST(OwnTrack, WithoutTheWayBackTheRobotStaysInThePocket)
{
  CaOptions o;
  o.retrace_own_track = false;
  PocketDrive d(o);
  const Pose2 out = stuck_in_pocket(&d, 40.0);
  EXPECT_GT(out.x(), 0.0) << d.ca.status();
}

// way_back itself: what is on the track now, and how far back it goes.
struct TrackedPocket
{
  TrackedPocket() : map(LocalMapOptions{}), track(OwnTrackOptions{}) {}
  void see(const Pose2& laser, const std::vector<Wall>& walls, double t)
  {
    map.add_scan(testing::scan_points(laser, walls, time::from_utime(static_cast<int64_t>(t * 1e6)), 6.0));
  }
  LocalMap map;
  OwnTrack track;
};

constexpr double kTrackRadius = 0.26, kTrackClearance = 0.36;

TrackedPocket pocket_track(const std::vector<Wall>& walls)
{
  TrackedPocket m;
  double t = 1.0;
  for (double x = -1.5; x <= 1.1 + 1e-9; x += 0.05, t += 0.1) {
    m.see(Pose2(x, 0.0, 0.0), walls, t);
    m.map.rebuild(time::from_utime(static_cast<int64_t>(t * 1e6)));
    m.track.add(Eigen::Vector2d(x, 0.0), m.map.clearance(Eigen::Vector2d(x, 0.0), kTrackClearance));
  }
  // Looking back toward the mouth (as a turn on the spot does).
  m.see(Pose2(1.1, 0.0, M_PI), walls, t);
  m.map.rebuild(time::from_utime(static_cast<int64_t>(t * 1e6)));
  return m;
}

TEST(OwnTrack, TheWayBackEndsPastThePocketsMouth)
{
  const auto walls = room_with_pocket();
  const TrackedPocket m = pocket_track(walls);
  const auto way = way_back(m.track, m.map, Eigen::Vector2d(1.1, 0.0), kTrackRadius, kTrackClearance, OwnTrackOptions{});
  ASSERT_TRUE(way);
  ASSERT_FALSE(way->corners.empty());
  // Along the centre line (one straight leg), ending beyond the mouth by about `beyond`.
  EXPECT_EQ(way->corners.size(), 1u);
  EXPECT_LT(way->corners.back().x(), -0.2);
  EXPECT_GT(way->corners.back().x(), -0.9);
  EXPECT_NEAR(way->corners.back().y(), 0.0, 1e-9);
}

TEST(OwnTrack, SomethingOnTheTrackNowClosesTheWayBack)
{
  auto walls = room_with_pocket();
  TrackedPocket m = pocket_track(walls);
  // Someone (or something) now stands in the pocket's mouth.
  walls.push_back({{0.25, -0.05}, {0.25, 0.05}});
  m.see(Pose2(1.1, 0.0, M_PI), walls, 20.0);
  m.map.rebuild(time::from_utime(20'000'000));
  const auto way = way_back(m.track, m.map, Eigen::Vector2d(1.1, 0.0), kTrackRadius, kTrackClearance, OwnTrackOptions{});
  // Up to it, short of the full clearance, is no way out.
  EXPECT_FALSE(way);
}

TEST(OwnTrack, NoWayBackWhereNothingIsTight)
{
  const TrackedPocket m = pocket_track(room_with_pocket());
  // Out in the room, on the track: the ordinary rules lead on from here.
  EXPECT_FALSE(way_back(m.track, m.map, Eigen::Vector2d(-0.9, 0.0), kTrackRadius, kTrackClearance, OwnTrackOptions{}));
}

TEST(OwnTrack, NoWayBackOffTheTrack)
{
  const TrackedPocket m = pocket_track(room_with_pocket());
  EXPECT_FALSE(way_back(m.track, m.map, Eigen::Vector2d(-2.0, 1.5), kTrackRadius, kTrackClearance, OwnTrackOptions{}));
}

TEST(OwnTrack, KeepsItsLengthAndStartsAnewAfterAJump)
{
  OwnTrackOptions o;
  o.max_length = 1.0;
  OwnTrack track(o);
  for (double x = 0.0; x <= 3.0; x += 0.05) track.add(Eigen::Vector2d(x, 0.0), 0.5);
  ASSERT_FALSE(track.points().empty());
  EXPECT_NEAR(track.points().back().at.x() - track.points().front().at.x(), 1.0, 0.06);
  track.add(Eigen::Vector2d(10.0, 0.0), 0.5);
  EXPECT_EQ(track.points().size(), 1u);
}

}  // namespace
}  // namespace rgnav::collision_avoidance
