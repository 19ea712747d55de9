// The two faces of a thin wall: one seen from a room, one from the corridor, 15 cm apart. A
// registration that pairs by distance alone snaps a scan of one face onto the other (the error
// found on loop closures in the simulated Freiburg79 building); with normals oriented toward
// the sensor that saw them, only the same face pairs.
#include <gtest/gtest.h>

#include <random>

#include "scan_mapper/icp.h"
#include "scan_mapper/point_map.h"

namespace sm = rgnav::scan_mapper;

namespace {

constexpr double kWall = 0.15;  // wall thickness [m]: corridor face at y = 0, room face at y = kWall

// Points along a segment every 5 cm, with a little range-like noise across it.
sm::Points segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, std::mt19937* rng)
{
  std::normal_distribution<double> noise(0.0, 0.003);
  const Eigen::Vector2d d = b - a;
  const Eigen::Vector2d across(-d.y() / d.norm(), d.x() / d.norm());
  const int n = static_cast<int>(d.norm() / 0.05);
  sm::Points out;
  for (int i = 0; i <= n; ++i) out.push_back(a + d * (static_cast<double>(i) / n) + across * noise(*rng));
  return out;
}

// Points seen from `viewpoint`, with their normals oriented toward it.
struct Seen
{
  sm::Points points, normals;
  std::vector<char> has_normal;
};

Seen seen_from(sm::Points points, const Eigen::Vector2d& viewpoint)
{
  const sm::PointMap own(points);
  Seen s{points, own.normals(), own.has_normals()};
  sm::orient_normals_toward(s.points, viewpoint, &s.normals, s.has_normal);
  return s;
}

void append(Seen* to, const Seen& from)
{
  to->points.insert(to->points.end(), from.points.begin(), from.points.end());
  to->normals.insert(to->normals.end(), from.normals.begin(), from.normals.end());
  to->has_normal.insert(to->has_normal.end(), from.has_normal.begin(), from.has_normal.end());
}

}  // namespace

TEST(PointMap, NormalsOrientedTowardTheViewpoint)
{
  std::mt19937 rng(3);
  const auto below = seen_from(segment({-1, 0}, {1, 0}, &rng), {0, -2});
  const auto above = seen_from(segment({-1, 0}, {1, 0}, &rng), {0, 2});
  int checked = 0;
  for (size_t i = 0; i < below.points.size(); ++i) {
    if (!below.has_normal[i] || !above.has_normal[i]) continue;
    EXPECT_LT(below.normals[i].y(), -0.9);
    EXPECT_GT(above.normals[i].y(), 0.9);
    ++checked;
  }
  EXPECT_GT(checked, 30);
}

TEST(PointMap, NearestWithNormalSkipsTheOtherFace)
{
  std::mt19937 rng(4);
  Seen model = seen_from(segment({-2, 0}, {2, 0}, &rng), {0, -2});        // corridor face
  append(&model, seen_from(segment({-2, kWall}, {2, kWall}, &rng), {0, 2}));  // room face
  const sm::PointMap map(model.points, model.normals, model.has_normal);
  // A room-face point placed nearer the corridor face pairs with the room face.
  const Eigen::Vector2d q(0.0, 0.05);
  const int any = map.nearest(q, 0.5);
  const int same_side = map.nearest(q, 0.5, Eigen::Vector2d(0, 1), 0.5);
  ASSERT_GE(any, 0);
  ASSERT_GE(same_side, 0);
  EXPECT_NEAR(map.points()[static_cast<size_t>(any)].y(), 0.0, 0.02);
  EXPECT_NEAR(map.points()[static_cast<size_t>(same_side)].y(), kWall, 0.02);
}

TEST(Icp, ThinWallFacesAreNotMatchedOntoEachOther)
{
  std::mt19937 rng(5);
  // The model (earlier scans): the wall seen from the corridor and from the room, and the
  // room's side wall, which fixes x.
  const Eigen::Vector2d corridor(0.0, -2.0), room(0.5, 1.5);
  Seen model = seen_from(segment({-3, 0}, {3, 0}, &rng), corridor);
  append(&model, seen_from(segment({-3, kWall}, {2, kWall}, &rng), room));
  append(&model, seen_from(segment({2, kWall + 0.1}, {2, 3}, &rng), room));
  const sm::PointMap map(model.points, model.normals, model.has_normal);
  // The scan from inside the room sees the room face and the side wall; its true pose is the
  // identity, the guess is 10 cm toward the corridor face (nearer to it than to the room face).
  Seen scan = seen_from(segment({-2.5, kWall}, {1.9, kWall}, &rng), room);
  append(&scan, seen_from(segment({2, kWall + 0.1}, {2, 2.5}, &rng), room));
  const sm::Pose2 guess{0.05, -0.1, 0.01};
  sm::IcpOptions o;

  const auto blind = sm::icp_point_to_line(scan.points, map, guess, o);
  ASSERT_TRUE(blind.ok);
  // Pairing by distance alone: the room face lands on the corridor face.
  EXPECT_NEAR(blind.map_from_scan.y(), -kWall, 0.03);

  const auto sided = sm::icp_point_to_line(scan.points, scan.normals, scan.has_normal, map, guess, o);
  ASSERT_TRUE(sided.ok);
  EXPECT_NEAR(sided.map_from_scan.x(), 0.0, 0.01);
  EXPECT_NEAR(sided.map_from_scan.y(), 0.0, 0.01);
  EXPECT_NEAR(sided.map_from_scan.theta(), 0.0, 0.005);
  EXPECT_GT(sided.inlier_ratio, 0.9);

  // 180 degrees switches the check off.
  o.max_normal_angle_deg = 180.0;
  const auto off = sm::icp_point_to_line(scan.points, scan.normals, scan.has_normal, map, guess, o);
  EXPECT_NEAR(off.map_from_scan.y(), blind.map_from_scan.y(), 1e-9);
}
