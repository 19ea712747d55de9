// Giving way sideways (give_way.h): the yield point lies out of the person's predicted path
// beside a doorway or beyond a hallway's mouth, never back along their path (as the old give-way
// line did: the failure it fixes); and waiting there lasts until nobody is left to pass.
#include <gtest/gtest.h>

#include <cmath>

#include "collision_avoidance/chain_planner.h"
#include "collision_avoidance/collision_avoidance.h"
#include "collision_avoidance/give_way.h"
#include "scan_fixture.h"

namespace rgnav::collision_avoidance {
namespace {

using testing::Wall;
constexpr double kClearance = 0.36;  // robot radius + safety margin

// The local map after scans from `at` facing each of `headings` (the laser looks ahead only).
LocalMap seen_from(const Eigen::Vector2d& at, const std::vector<double>& headings, const std::vector<Wall>& walls)
{
  LocalMap map(LocalMapOptions{});
  int64_t us = 1'000'000;
  for (const double h : headings) {
    us += 100'000;
    map.add_scan(testing::scan_points(Pose2(at, h), walls, time::from_utime(us), map.max_range()));
  }
  map.rebuild(time::from_utime(us));
  return map;
}

// A wall across x = 1 with a doorway 0.9 m wide at y = 0; a person (a 0.4 m box) in it.
std::vector<Wall> doorway_with_person()
{
  std::vector<Wall> w = {{{1.0, -3.0}, {1.0, -0.45}}, {{1.0, 0.45}, {1.0, 3.0}}};
  for (const auto& side : testing::box(1.1, -0.2, 1.5, 0.2)) w.push_back(side);
  return w;
}

// Turns on the spot and straight legs through the corners (how the robot drives there).
trajectory::Chain polyline(Pose2 from, const std::vector<Eigen::Vector2d>& corners)
{
  trajectory::Chain c;
  for (const auto& p : corners) {
    const Eigen::Vector2d d = p - from.translation();
    const double dth = geometry::normalize_angle(std::atan2(d.y(), d.x()) - from.theta());
    if (std::fabs(dth) > 1e-3) {
      c.push_back(trajectory::Segment::turn(from, dth));
      from = c.end();
    }
    c.push_back(trajectory::Segment::line(from, d.norm()));
    from = c.end();
  }
  return c;
}

TEST(YieldPoint, SidewaysBesideADoorwayNotBackAlongThePersonsPath)
{
  const Eigen::Vector2d robot(0.0, 0.0);
  const LocalMap map = seen_from(robot, {0.0, M_PI}, doorway_with_person());
  PersonPath path;
  path.from = {1.3, 0.0};
  path.direction = {-1.0, 0.0};  // coming through the door, at the robot
  const YieldOptions o;
  const auto y = choose_yield_point(map, robot, path, kClearance, o);
  ASSERT_TRUE(y.has_value());
  const double off_needed = kClearance + o.path_half_width + o.extra;
  EXPECT_GE(y->off_path, off_needed - 1e-9);
  EXPECT_GE(std::fabs(y->point.y()), off_needed - 1e-9) << "out of the path sideways";
  EXPECT_LT(path.along(y->point) - path.along(robot), 1.0) << "not far back down the person's path";
  EXPECT_LT(y->travel, 2.5);
  ASSERT_FALSE(y->corners.empty());
  EXPECT_NEAR((y->corners.back() - y->point).norm(), 0.0, 1e-9);
  EXPECT_FALSE(first_collision(polyline(Pose2(robot, 0.0), y->corners), map, kClearance, 0.05).has_value());

  // The old give-way, for comparison: straight back, away from the target, which is the
  // person's path; its whole line stays in it (they walk up again and wait again).
  const auto old = choose_give_way(map, robot, M_PI, kClearance, 0.05, GiveWayOptions{});
  ASSERT_TRUE(old.has_value());
  const Eigen::Vector2d end = robot + old->length * Eigen::Vector2d(std::cos(old->heading), std::sin(old->heading));
  EXPECT_LT(path.distance(end), kClearance + o.path_half_width);
}

TEST(YieldPoint, BeyondTheMouthOfAHallwayOnceTheRobotLookedBehind)
{
  // A hallway 1.1 m wide along x over [-3, 3], the robot in it, a person ahead coming its way;
  // behind the robot, past the mouth, a room (its wall along x = -3).
  std::vector<Wall> w = {{{-3.0, -0.55}, {3.0, -0.55}}, {{-3.0, 0.55}, {3.0, 0.55}},
                         {{-3.0, 0.55}, {-3.0, 4.0}},   {{-3.0, -0.55}, {-3.0, -4.0}}};
  for (const auto& side : testing::box(0.0, -0.2, 0.4, 0.2)) w.push_back(side);
  PersonPath path;
  path.from = {0.2, 0.0};
  path.direction = {-1.0, 0.0};
  const YieldOptions o;
  const double off_needed = kClearance + o.path_half_width + o.extra;
  for (const double x : {-1.0, -2.4}) {
    const Eigen::Vector2d robot(x, 0.0);
    // Facing the person only: nothing known behind, no place out of the way.
    EXPECT_FALSE(choose_yield_point(seen_from(robot, {0.0}, w), robot, path, kClearance, o).has_value()) << x;
    // Having turned to look: out of the hallway and aside (from deep in it, the room is seen
    // through the mouth only: farther out), off the person's line however far they walk on.
    const LocalMap map = seen_from(robot, {0.0, M_PI}, w);
    const auto y = choose_yield_point(map, robot, path, kClearance, o);
    ASSERT_TRUE(y.has_value()) << x;
    EXPECT_LT(y->point.x(), -3.0 - kClearance) << x;
    EXPECT_GE(std::fabs(y->point.y()), off_needed - 1e-9) << x;
    EXPECT_LE(y->travel, o.max_travel) << x;
    EXPECT_FALSE(first_collision(polyline(Pose2(robot, M_PI), y->corners), map, kClearance, 0.05).has_value()) << x;
    // Near the mouth the room beside it is in view: the place is right beside the mouth.
    if (x < -2.0) {
      EXPECT_GT(y->point.x(), -3.0 - kClearance - 1.0) << x;
    }
  }
}

TEST(YieldPoint, NothingWhenBoxedIn)
{
  const Eigen::Vector2d robot(0.0, 0.0);
  const LocalMap map = seen_from(robot, {0.0, M_PI_2, M_PI, -M_PI_2}, testing::box(-0.6, -0.6, 0.6, 0.6));
  PersonPath path;
  path.from = {0.5, 0.0};
  path.direction = {-1.0, 0.0};
  EXPECT_FALSE(choose_yield_point(map, robot, path, kClearance, YieldOptions{}).has_value());
}

TEST(YieldPoint, AlreadyOutOfThePathIsWhereItWaits)
{
  const Eigen::Vector2d robot(0.0, 2.0);
  const LocalMap map = seen_from(robot, {0.0, M_PI}, {});
  PersonPath path;
  path.from = {3.0, 0.0};
  path.direction = {-1.0, 0.0};
  const auto y = choose_yield_point(map, robot, path, kClearance, YieldOptions{});
  ASSERT_TRUE(y.has_value());
  EXPECT_TRUE(y->corners.empty());
  EXPECT_DOUBLE_EQ(y->travel, 0.0);
}

// A person (0.4 m box) walking along y = 0 from x0 to x1 at 1 m/s, scanned at 10 Hz by a robot
// standing at (0, 1.4) facing `facing`; the map after the walk.
LocalMap watch_walk(double x0, double x1, double facing)
{
  LocalMap map(LocalMapOptions{});
  const Eigen::Vector2d robot(0.0, 1.4);
  const double dir = x1 > x0 ? 1.0 : -1.0;
  int64_t us = 1'000'000;
  for (double x = x0; dir * (x1 - x) >= -1e-9; x += dir * 0.1) {
    us += 100'000;
    map.add_scan(testing::scan_points(Pose2(robot, facing), testing::box(x - 0.2, -0.2, x + 0.2, 0.2),
                                      time::from_utime(us), map.max_range()));
    map.rebuild(time::from_utime(us));
  }
  return map;
}

TEST(SomeoneToPass, WhileTheyComeNotOnceTheyPassedOrTurnedBack)
{
  PersonPath path;
  path.from = {3.0, 0.0};
  path.direction = {-1.0, 0.0};
  const Eigen::Vector2d robot(0.0, 1.4);
  const YieldOptions o;
  // Coming, still on the robot's far side of it along the path.
  EXPECT_EQ(someone_to_pass(watch_walk(3.0, 1.0, 0.0), path, robot, o), ToPass::kWalking);
  // Past the robot (and walking on): nobody left to pass.
  EXPECT_EQ(someone_to_pass(watch_walk(3.0, -2.0, -M_PI_2), path, robot, o), ToPass::kNobody);
  // Turned back, walking away up the path: not coming.
  EXPECT_EQ(someone_to_pass(watch_walk(1.0, 3.0, 0.0), path, robot, o), ToPass::kNobody);
  // Nobody there at all.
  EXPECT_EQ(someone_to_pass(seen_from(robot, {0.0}, {}), path, robot, o), ToPass::kNobody);
}


// A room (x < 1.5, |y| < 3), a hallway `width` wide from x = 1.5 to 5.5, a room beyond (x > 5.5).
std::vector<Wall> room_hallway_room(double width)
{
  const double h = width / 2;
  return {{{1.5, -3.0}, {1.5, -h}}, {{1.5, h}, {1.5, 3.0}},  // the near room's far wall, the mouth
          {{1.5, -h}, {5.5, -h}},   {{1.5, h}, {5.5, h}},    // the hallway
          {{5.5, -3.0}, {5.5, -h}}, {{5.5, h}, {5.5, 3.0}},  // the far room's wall
          {{-3.0, -3.0}, {1.5, -3.0}}, {{-3.0, 3.0}, {1.5, 3.0}}, {{-3.0, -3.0}, {-3.0, 3.0}}};
}

std::vector<Wall> with_person(std::vector<Wall> w, const Eigen::Vector2d& at)
{
  for (const auto& side : testing::box(at.x() - 0.2, at.y() - 0.2, at.x() + 0.2, at.y() + 0.2)) w.push_back(side);
  return w;
}

constexpr double kOneLaneWidth = 2.0 * (kClearance + 0.45);  // the robot beside a person passing (YieldOptions)

TEST(OneLane, TheHallwayBetweenThemNotAWideCorridorNorThePersonThemselves)
{
  // The robot drove up to the hallway, seeing it ahead; the person is in the room beyond.
  auto map_at = [](const std::vector<Wall>& w, double x) {
    LocalMap map(LocalMapOptions{});
    int64_t us = 1'000'000;
    for (double from = x - 1.0; from <= x + 1e-9; from += 0.25) {
      us += 100'000;
      map.add_scan(testing::scan_points(Pose2(from, 0.0, 0.0), w, time::from_utime(us), map.max_range()));
    }
    map.rebuild(time::from_utime(us));
    return map;
  };
  const Eigen::Vector2d robot(0.0, 0.0), beyond(6.5, 0.0);
  const auto lane = one_lane_between(map_at(with_person(room_hallway_room(1.1), beyond), 0.0), robot, beyond,
                                     kOneLaneWidth, 0.3);
  ASSERT_TRUE(lane.has_value());
  EXPECT_NEAR(lane->length, 6.2, 1e-9);
  EXPECT_NEAR(lane->begin, 1.5 - kOneLaneSlab, 0.11) << "from the mouth";
  // To the far mouth (the last points on walls seen at a grazing angle from 5 m lie up to half a
  // metre short of it, with the laser's 1 degree), short of the person.
  EXPECT_GT(lane->end, 5.5 - 0.5);
  EXPECT_LT(lane->end, 5.5 + kOneLaneSlab + 0.11);
  EXPECT_GT(lane->length - lane->end, 0.5);

  // The robot in the hallway: the stretch begins where it is. The person in it: it reaches them.
  const Eigen::Vector2d inside(2.5, 0.0), person_in(4.5, 0.0);
  const auto from_inside = one_lane_between(map_at(with_person(room_hallway_room(1.1), beyond), 2.5), inside, beyond,
                                            kOneLaneWidth, 0.3);
  ASSERT_TRUE(from_inside.has_value());
  EXPECT_DOUBLE_EQ(from_inside->begin, 0.0);
  const auto to_them = one_lane_between(map_at(with_person(room_hallway_room(1.1), person_in), 0.0), robot, person_in,
                                        kOneLaneWidth, 0.3);
  ASSERT_TRUE(to_them.has_value());
  EXPECT_NEAR(to_them->end, to_them->length, 0.1);

  // A corridor where a robot and a person pass each other (2.4 m), the person in it: the
  // person's own points do not make it narrow. Nothing around at all: room everywhere.
  EXPECT_FALSE(one_lane_between(map_at(with_person(room_hallway_room(2.4), person_in), 0.0), robot, person_in,
                                kOneLaneWidth, 0.3)
                   .has_value());
  EXPECT_FALSE(one_lane_between(map_at(with_person({}, person_in), 0.0), robot, person_in, kOneLaneWidth, 0.3).has_value());
}

// Collision avoidance standing at `robot` (facing the hallway) with targets through the hallway
// of room_hallway_room(width), while a person walks from x0 toward it along y = 0 at 0.8 m/s:
// the person's x when it first began to yield (NaN: it did not before they came within `until`).
double yielded_at(double width, const Eigen::Vector2d& robot, double x0, double until)
{
  CaOptions o;
  CollisionAvoidance ca(o);
  Targets t;
  t.goal_id = 1;
  for (double x = robot.x() + 1.0; x <= 9.0 + 1e-9; x += 1.0) t.poses.emplace_back(x, 0.0, 0.0);
  ca.set_targets(t);
  const Pose2 pose(robot, 0.0);
  int64_t us = 1'000'000;
  // Standing there a while first: the walls count as static (they have been seen for a second),
  // and nobody is in view yet; then the person walks in.
  for (int i = 0; i < 20; ++i) {
    us += 100'000;
    ca.on_odometry(time::from_utime(us), pose, 0.0);
    ca.on_scan(time::from_utime(us), testing::cast(pose * o.base_from_laser, room_hallway_room(width)), 8.0);
    ca.on_drive_feedback({0, 0, 0.0, 0.0, 0.0});
    ca.update(time::from_utime(us));
  }
  for (double x = x0; x > until; x -= 0.08) {
    us += 100'000;
    const auto w = with_person(room_hallway_room(width), {x, 0.0});
    ca.on_odometry(time::from_utime(us), pose, 0.0);
    ca.on_scan(time::from_utime(us), testing::cast(pose * o.base_from_laser, w), 8.0);
    ca.on_drive_feedback({0, 0, 0.0, 0.0, 0.0});
    ca.update(time::from_utime(us));
    if (ca.mode() == Mode::kYielding) return x;
  }
  return std::nan("");
}

TEST(YieldBeforeOneLane, OutOfTheirWayBeforeTheHallwayNotInIt)
{
  // Before the hallway, someone coming through it: it yields while a chain into the hallway is
  // still free (they are farther than the targets it plans to), not once they block it.
  const double x = yielded_at(1.1, {0.5, 0.0}, 5.0, 2.5);
  EXPECT_FALSE(std::isnan(x)) << "it waited to meet them in the hallway";
  EXPECT_GT(x, 3.5);
  // A corridor wide enough to pass each other (their predicted places left out of its width).
  // No reason to yield while they are far (nearer, no chain gets past them standing there: the
  // fallback's own yield, as before).
  EXPECT_TRUE(std::isnan(yielded_at(2.4, {0.5, 0.0}, 5.0, 3.4)));
  // Nearly through the hallway, someone in the room beyond walking up to it: it was in there
  // first and goes on (backing out through the whole hallway would cost both far more).
  // (Until they come so near that no chain gets past them: the fallback's yield, as before.)
  EXPECT_TRUE(std::isnan(yielded_at(1.1, {4.7, 0.0}, 8.5, 7.6)));
}


// The way out of a person's path from inside a hallway, as collision avoidance sends it: it
// turns round on the spot where it stands (it cannot drive backwards), but at the hallway's mouth
// it drives on round the corner into the room beside it instead of stopping to turn there (the
// corners of the way there are rounded where its legs leave room). The person following it out
// (or waiting for it) loses patience only while it stands: people who waited through its first
// turn turned back at its second, for good, and came again as it went back in.
TEST(YieldManoeuvre, RoundsTheCornerAtTheHallwaysMouthWithoutStopping)
{
  CaOptions o;
  CollisionAvoidance ca(o);
  Targets t;
  t.goal_id = 1;
  for (double x = 3.0; x <= 9.0 + 1e-9; x += 1.0) t.poses.emplace_back(x, 0.0, 0.0);
  ca.set_targets(t);
  const std::vector<Wall> hallway = room_hallway_room(1.1);
  Pose2 pose(2.3, 0.0, 0.0);  // in the hallway (x 1.5 to 5.5), 0.8 m past its mouth
  int64_t us = 1'000'000;
  std::optional<trajectory::Trajectory> leaving;
  int64_t ended = 0;  // the manoeuvre the drive reports done (a turn on the spot: the pose turned)
  // Standing a while (the walls turn static), then someone walks down the hallway at it.
  for (int i = 0; i < 120 && !leaving; ++i) {
    us += 100'000;
    const double x = i < 20 ? 20.0 : std::max(3.4, 6.5 - 0.08 * (i - 20));
    const auto w = i < 20 ? hallway : with_person(hallway, {x, 0.0});
    ca.on_odometry(time::from_utime(us), pose, 0.0);
    ca.on_scan(time::from_utime(us), testing::cast(pose * o.base_from_laser, w), 8.0);
    ca.on_drive_feedback({ended, ended ? 2 : 0, 0.0, 0.0, 0.0});
    const auto sent = ca.update(time::from_utime(us));
    if (!sent || sent->chain.empty()) continue;
    if (ca.mode() != Mode::kYielding) continue;
    bool turns_only = true;
    for (const auto& s : sent->chain.segments()) turns_only = turns_only && s.kind() == trajectory::Kind::kTurn;
    if (!turns_only) {
      leaving = sent;
    } else {  // looking behind: the turn done at once
      pose = sent->chain.end();
      ended = sent->id;
    }
  }
  ASSERT_TRUE(leaving.has_value()) << ca.status();
  const auto& segs = leaving->chain.segments();
  size_t first_line = segs.size(), last_line = 0;
  for (size_t i = 0; i < segs.size(); ++i)
    if (segs[i].kind() == trajectory::Kind::kLine) {
      first_line = std::min(first_line, i);
      last_line = i;
    }
  std::string shape;  // kind and end of every segment, for the messages
  for (const auto& s : segs) {
    const Pose2 e = s.end();
    shape += std::to_string(static_cast<int>(s.kind())) + "(" + std::to_string(e.x()).substr(0, 5) + "," +
             std::to_string(e.y()).substr(0, 5) + ") ";
  }
  ASSERT_LT(first_line, last_line) << "a way out round the mouth has more than one leg: " << shape;
  EXPECT_LT(leaving->chain.end().x(), 1.5) << "out of the hallway: " << shape;
  // From the first leg until it is out of the hallway and clear of its mouth, it keeps driving.
  for (size_t i = first_line; i < segs.size() && segs[i].start().x() > 1.5 - kClearance; ++i)
    EXPECT_NE(segs[i].kind(), trajectory::Kind::kTurn) << "a stop to turn on the spot at the mouth, segment " << i << ": " << shape;
  EXPECT_FALSE(first_collision(leaving->chain, ca.map(), kClearance, 0.05).has_value());
}

}  // namespace
}  // namespace rgnav::collision_avoidance
