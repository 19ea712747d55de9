// Rectangles from one view (vision/rectangle3d.h, diss. 3.3): exact for exact projections,
// whatever the rectangle's pose, from one measured corner; the normal points toward the camera;
// what is no projection of a rectangle in front of the camera gives nothing.
#include "vision/rectangle3d.h"
#include "vision/image_quadrangles.h"
#include "vision/object_rectangles.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

namespace rgnav::vision {
namespace {

const Pinhole kCamera{450.0, 452.0, 321.5, 238.0};

// A door-sized rectangle (2.10 x 1.01 m) centred at `centre`, turned by `r`; corners in order.
std::array<Eigen::Vector3d, 4> door(const Eigen::Vector3d& centre, const Eigen::Matrix3d& r)
{
  const double h = 1.05, w = 0.505;
  return {centre + r * Eigen::Vector3d(-w, -h, 0), centre + r * Eigen::Vector3d(w, -h, 0),
          centre + r * Eigen::Vector3d(w, h, 0), centre + r * Eigen::Vector3d(-w, h, 0)};
}

Quadrangle project(const std::array<Eigen::Vector3d, 4>& c)
{
  return {kCamera.project(c[0]), kCamera.project(c[1]), kCamera.project(c[2]), kCamera.project(c[3])};
}

TEST(Rectangle3d, ExactProjectionsGiveTheRectangleFromOneCorner)
{
  int checked = 0;
  for (double ax : {0.0, 0.4, -0.7})
    for (double ay : {0.0, 0.6, -1.0})
      for (double az : {0.0, 0.3}) {
        const Eigen::Matrix3d r = (Eigen::AngleAxisd(ax, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(ay, Eigen::Vector3d::UnitY()) *
                                   Eigen::AngleAxisd(az, Eigen::Vector3d::UnitZ()))
                                      .toRotationMatrix();
        const auto truth = door({0.3, -0.2, 4.0}, r);
        for (int known = 0; known < 4; ++known) {
          std::array<std::optional<Eigen::Vector3d>, 4> measured;
          measured[known] = truth[known];
          const auto rect = reconstruct_rectangle(project(truth), kCamera, measured);
          ASSERT_TRUE(rect) << ax << " " << ay << " " << az;
          for (int i = 0; i < 4; ++i) EXPECT_LT((rect->corners[i] - truth[i]).norm(), 1e-6) << ax << " " << ay << " " << az;
          EXPECT_NEAR(rect->side_a, 1.01, 1e-6);
          EXPECT_NEAR(rect->side_b, 2.10, 1e-6);
          // Toward the camera: from the rectangle's centre, the camera lies on the normal's side.
          const Eigen::Vector3d centre = (truth[0] + truth[2]) / 2.0;
          EXPECT_GT(rect->normal.dot(-centre), 0.0);
          EXPECT_NEAR(std::fabs(rect->normal.dot(r.col(2))), 1.0, 1e-9);
          ++checked;
        }
      }
  EXPECT_EQ(checked, 72);
}

TEST(Rectangle3d, AMeasuredCornerOffItsRayIsMovedOntoIt)
{
  const auto truth = door({0.0, 0.0, 3.0}, Eigen::Matrix3d::Identity());
  std::array<std::optional<Eigen::Vector3d>, 4> measured;
  measured[0] = truth[0] + Eigen::Vector3d(0.05, -0.05, 0.0);  // sideways off the ray: no depth error
  measured[2] = truth[2];
  const auto rect = reconstruct_rectangle(project(truth), kCamera, measured);
  ASSERT_TRUE(rect);
  for (int i = 0; i < 4; ++i) EXPECT_LT((rect->corners[i] - truth[i]).norm(), 0.01);
}

TEST(Rectangle3d, NoRectangleWithoutDepthOrFromADegenerateQuadrangle)
{
  const auto truth = door({0.0, 0.0, 3.0}, Eigen::Matrix3d::Identity());
  EXPECT_FALSE(reconstruct_rectangle(project(truth), kCamera, {}));
  Quadrangle collapsed = project(truth);
  collapsed[1] = collapsed[0];
  std::array<std::optional<Eigen::Vector3d>, 4> measured;
  measured[0] = truth[0];
  EXPECT_FALSE(reconstruct_rectangle(collapsed, kCamera, measured));
  // A measured corner behind the camera is no measurement.
  measured[0] = -truth[0];
  EXPECT_FALSE(reconstruct_rectangle(project(truth), kCamera, measured));
}

// The fit keeps an exact reconstruction exact, and with corners on whole pixels it is nearer the
// truth than the vanishing line's where that one is poor (sharp and flat angles).
TEST(Rectangle3d, RefinedFitStaysExactAndBeatsTheVanishingLineOnWholePixels)
{
  const Eigen::Matrix3d tilted =
      (Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(0.9, Eigen::Vector3d::UnitY())).toRotationMatrix();
  const auto truth = door({0.2, 0.1, 4.0}, tilted);
  std::array<std::optional<Eigen::Vector3d>, 4> measured;
  for (int i = 0; i < 4; ++i) measured[i] = truth[i];
  const auto exact = reconstruct_rectangle(project(truth), kCamera, measured);
  ASSERT_TRUE(exact);
  const auto kept = refine_rectangle(project(truth), kCamera, *exact, measured);
  ASSERT_TRUE(kept);
  for (int i = 0; i < 4; ++i) EXPECT_LT((kept->corners[i] - truth[i]).norm(), 1e-4);

  double paper_sum = 0.0, refined_sum = 0.0;
  int n = 0;
  for (double ax = -1.3; ax <= 1.3; ax += 0.26)
    for (double ay = -1.3; ay <= 1.3; ay += 0.26) {
      const Eigen::Matrix3d r = (Eigen::AngleAxisd(ax, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(ay, Eigen::Vector3d::UnitY())).toRotationMatrix();
      const auto t = door({0.0, 0.0, 4.0}, r);
      Quadrangle q = project(t);
      for (auto& p : q) p = p.array().round();
      std::array<std::optional<Eigen::Vector3d>, 4> m;
      m[0] = t[0];
      const auto paper = reconstruct_rectangle(q, kCamera, m);
      ASSERT_TRUE(paper);
      const auto refined = refine_rectangle(q, kCamera, *paper, m);
      ASSERT_TRUE(refined);
      for (int i = 0; i < 4; ++i) {
        paper_sum += (paper->corners[i] - t[i]).norm();
        refined_sum += (refined->corners[i] - t[i]).norm();
      }
      ++n;
    }
  EXPECT_GT(n, 90);
  EXPECT_LT(refined_sum, 0.7 * paper_sum) << "mean corner error: vanishing line " << paper_sum / (4 * n)
                                          << " m, refined " << refined_sum / (4 * n) << " m";
}

// Into the base frame: a camera 1.25 m up looking along the base's x sees a door frame 3 m
// ahead: its height is the vertical side whichever way the corners run, it is a door, and a
// level rectangle at table height is a table top.
TEST(Rectangle3d, ObjectsInTheBaseFrameWithTheirKind)
{
  Eigen::Isometry3d base_from_camera = Eigen::Isometry3d::Identity();
  base_from_camera.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;  // optical z forward = base x, x right = -y, y down = -z
  base_from_camera.translation() = Eigen::Vector3d(0.05, 0.0, 1.25);
  const Eigen::Isometry3d camera_from_base = base_from_camera.inverse();
  auto in_camera = [&](const std::array<Eigen::Vector3d, 4>& base) {
    Rectangle3d r;
    for (int i = 0; i < 4; ++i) r.corners[i] = camera_from_base * base[i];
    r.normal = camera_from_base.linear() * Eigen::Vector3d(-1, 0, 0);
    return r;
  };
  const std::array<Eigen::Vector3d, 4> door{Eigen::Vector3d(3, 0.5, 0), Eigen::Vector3d(3, 0.5, 2.1), Eigen::Vector3d(3, -0.5, 2.1),
                                            Eigen::Vector3d(3, -0.5, 0)};
  const ObjectRectangle o = to_object(in_camera(door), base_from_camera);
  EXPECT_NEAR(o.height, 2.1, 1e-9);
  EXPECT_NEAR(o.width, 1.0, 1e-9);
  EXPECT_EQ(o.kind, 1);
  EXPECT_NEAR(o.normal.x(), -1.0, 1e-9);
  // Counter-clockwise seen from the front (from -x): the turn of its corners points along the normal.
  EXPECT_GT((o.corners[1] - o.corners[0]).cross(o.corners[2] - o.corners[1]).dot(o.normal), 0.0);
  // Lifted off the floor (a whiteboard of a door's size): no door.
  std::array<Eigen::Vector3d, 4> high = door;
  for (auto& c : high) c.z() += 0.5;
  EXPECT_EQ(to_object(in_camera(high), base_from_camera).kind, 0);
  // Level at 0.72 m: a table top.
  Rectangle3d table = in_camera({Eigen::Vector3d(2, 0.6, 0.72), Eigen::Vector3d(2, -0.6, 0.72), Eigen::Vector3d(2.8, -0.6, 0.72),
                                 Eigen::Vector3d(2.8, 0.6, 0.72)});
  table.normal = camera_from_base.linear() * Eigen::Vector3d(0, 0, 1);
  EXPECT_EQ(to_object(table, base_from_camera).kind, 4);
}

// Whiteboards and monitors (the kinds beside doors): an upright rectangle on the wall
// above the floor is a whiteboard when its inside is white, whatever its size from Table 3.1's
// 0.3 m board to a 1.4 m one; the same outline not white is a picture (unknown); a landscape
// screen-sized one standing at desk height and not white is a monitor, white it is a small board.
TEST(Rectangle3d, WhiteboardsByWhatIsOnThemMonitorsBySizeAndPlace)
{
  Eigen::Isometry3d base_from_camera = Eigen::Isometry3d::Identity();
  base_from_camera.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  base_from_camera.translation() = Eigen::Vector3d(0.05, 0.0, 1.25);
  const Eigen::Isometry3d camera_from_base = base_from_camera.inverse();
  // Upright at x = 3, facing the robot: width along y, from z0 to z1.
  auto upright = [&](double width, double z0, double z1) {
    Rectangle3d r;
    const std::array<Eigen::Vector3d, 4> c{Eigen::Vector3d(3, 0.5 * width, z0), Eigen::Vector3d(3, 0.5 * width, z1),
                                           Eigen::Vector3d(3, -0.5 * width, z1), Eigen::Vector3d(3, -0.5 * width, z0)};
    for (int i = 0; i < 4; ++i) r.corners[i] = camera_from_base * c[i];
    r.normal = camera_from_base.linear() * Eigen::Vector3d(-1, 0, 0);
    return r;
  };
  constexpr int kUnknown = 0, kWhiteboard = 2, kMonitor = 3;
  const double white = 225.0, dark = 60.0;
  EXPECT_EQ(to_object(upright(1.4, 1.0, 1.9), base_from_camera, {}, white).kind, kWhiteboard);
  EXPECT_EQ(to_object(upright(0.302, 1.3, 1.514), base_from_camera, {}, white).kind, kWhiteboard);
  EXPECT_EQ(to_object(upright(1.4, 1.0, 1.9), base_from_camera, {}, dark).kind, kUnknown);   // a picture
  EXPECT_EQ(to_object(upright(1.4, 1.0, 1.9), base_from_camera).kind, kUnknown);             // nothing seen inside
  EXPECT_EQ(to_object(upright(0.6, 1.1, 1.9), base_from_camera, {}, dark).kind, kUnknown);   // a portrait poster
  EXPECT_EQ(to_object(upright(1.4, 0.0, 0.9), base_from_camera, {}, white).kind, kUnknown);  // down to the floor: a box's face
  // A 20-inch screen on a desk (0.75 m), 0.44 x 0.27 m.
  EXPECT_EQ(to_object(upright(0.44, 0.85, 1.12), base_from_camera, {}, dark).kind, kMonitor);
  EXPECT_EQ(to_object(upright(0.44, 0.85, 1.12), base_from_camera, {}, white).kind, kWhiteboard);
  EXPECT_EQ(to_object(upright(0.44, 1.6, 1.87), base_from_camera, {}, dark).kind, kUnknown);  // hung high: a picture
}

TEST(Rectangle3d, InternalAnglesOfASquareAndASkewedOne)
{
  const Quadrangle square{Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 0), Eigen::Vector2d(10, 10), Eigen::Vector2d(0, 10)};
  for (double a : internal_angles(square)) EXPECT_NEAR(a, M_PI / 2, 1e-12);
  const Quadrangle skew{Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 0), Eigen::Vector2d(20, 10), Eigen::Vector2d(10, 10)};
  const auto a = internal_angles(skew);
  EXPECT_NEAR(a[0], M_PI / 4, 1e-12);
  EXPECT_NEAR(a[1], 3 * M_PI / 4, 1e-12);
  EXPECT_NEAR(a[0] + a[1] + a[2] + a[3], 2 * M_PI, 1e-12);
}

// Image lines (diss. 3.1.1): pieces of one edge merge, also through a piece that joins two
// that lie too far apart on their own; a parallel edge 4 px beside stays; short ones go; a
// short piece may lean more than alpha_max, a long line may not.
TEST(ImageSegments, PiecesOfOneEdgeMergeAndParallelEdgesStayApart)
{
  QuadrangleOptions o;
  std::vector<ImageSegment> segs{
      {Eigen::Vector2d(0, 100), Eigen::Vector2d(100, 100.5)},     // a piece of an edge ...
      {Eigen::Vector2d(300, 101.5), Eigen::Vector2d(400, 102)},   // ... 200 px on: too far for D_gap alone ...
      {Eigen::Vector2d(150, 100.8), Eigen::Vector2d(250, 101.2)}, // ... this piece joins them (given last)
      {Eigen::Vector2d(0, 104), Eigen::Vector2d(400, 106)},       // the parallel edge beside it
      {Eigen::Vector2d(50, 300), Eigen::Vector2d(60, 300)}};      // shorter than L_min
  const auto merged = merge_segments(segs, o);
  ASSERT_EQ(merged.size(), 2u);
  for (const auto& m : merged) EXPECT_NEAR((m.b - m.a).norm(), 400.0, 0.1);
  // Without the joining piece the two far pieces stay apart.
  segs.erase(segs.begin() + 2);
  EXPECT_EQ(merge_segments(segs, o).size(), 3u);
  // A 21 px piece continuing an edge leans 1.6 degrees (its ends are found to a pixel or so):
  // beyond alpha_max (1 degree), within what its length is good for, so it joins the edge.
  const std::vector<ImageSegment> edge{{Eigen::Vector2d(0, 100), Eigen::Vector2d(200, 100)},
                                       {Eigen::Vector2d(205, 100), Eigen::Vector2d(226, 100.6)}};
  const auto joined = merge_segments(edge, o);
  ASSERT_EQ(joined.size(), 1u);
  EXPECT_NEAR((joined[0].b - joined[0].a).norm(), 226.0, 0.1);
  // Two 100 px lines crossing at 1.6 degrees (within D_L of each other) are two lines.
  EXPECT_EQ(merge_segments({{Eigen::Vector2d(0, 100), Eigen::Vector2d(100, 100)},
                            {Eigen::Vector2d(0, 98.6), Eigen::Vector2d(100, 101.4)}}, o).size(), 2u);
}

}  // namespace
}  // namespace rgnav::vision
