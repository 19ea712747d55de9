// Which points of a scan get a surface normal: from their neighbours where those are dense
// enough, else from their two neighbours in beam order where the three lie on one surface.
#include <gtest/gtest.h>

#include <cmath>

#include "scan_mapper/scan_normals.h"

namespace sm = rgnav::scan_mapper;

namespace {

const Eigen::Vector2d kLaser(0.0, 0.0);

// Where a 1 deg scanner at the origin sees the wall y = wall_y, beams from a0 to a1 [deg].
sm::Points wall_samples(double wall_y, double a0, double a1)
{
  sm::Points out;
  for (double a = a0; a <= a1 + 1e-9; a += 1.0) {
    const double rad = a * M_PI / 180.0;
    out.emplace_back(wall_y / std::tan(rad), wall_y);
  }
  return out;
}

sm::ScanNormalOptions beam_normals_on()
{
  sm::ScanNormalOptions o;
  o.beam_max_gap_m = 1.0;
  o.beam_max_bend_rad = 5.74 * M_PI / 180.0;
  return o;
}

}  // namespace

TEST(ScanNormals, AFarWallsSparseSamplesTakeTheChordOfTheirBeamNeighbours)
{
  // A wall 1 m to the left seen at grazing incidence (9-20 deg): samples 0.05-0.6 m apart.
  const sm::Points wall = wall_samples(1.0, 9.0, 20.0);
  ASSERT_GT((wall[1] - wall[0]).norm(), 0.5);
  const auto without = sm::scan_normals(wall, kLaser, sm::ScanNormalOptions{});
  const auto with = sm::scan_normals(wall, kLaser, beam_normals_on());
  EXPECT_EQ(without.has_normal[1], 0) << "the first samples are too sparse for a normal from the neighbours";
  for (size_t i = 1; i + 1 < wall.size(); ++i) {
    ASSERT_TRUE(with.has_normal[i]) << i;
    // Across the wall, toward the laser.
    EXPECT_NEAR(with.normals[i].y(), -1.0, 1e-6) << i;
  }
  // The ends have one beam neighbour only.
  EXPECT_EQ(with.has_normal.front(), without.has_normal.front());
  EXPECT_EQ(with.has_normal.back(), without.has_normal.back());
}

TEST(ScanNormals, ACornerAnOcclusionEdgeAndAGapGetNone)
{
  // A corner: along x, then along y, 0.5 m steps.
  const sm::Points corner = {{3.0, 1.0}, {3.5, 1.0}, {4.0, 1.0}, {4.0, 1.5}, {4.0, 2.0}};
  const auto c = sm::scan_normals(corner, kLaser, beam_normals_on());
  EXPECT_EQ(c.has_normal[2], 0);
  EXPECT_TRUE(c.has_normal[1]);
  EXPECT_TRUE(c.has_normal[3]);

  // An occlusion edge: a near object's last sample, then the wall behind it.
  const sm::Points edge = {{2.0, 0.5}, {2.0, 0.8}, {5.0, 2.3}, {5.0, 2.8}};
  const auto e = sm::scan_normals(edge, kLaser, beam_normals_on());
  EXPECT_EQ(e.has_normal[1], 0);
  EXPECT_EQ(e.has_normal[2], 0);

  // A point repeated three times (no thinning): the middle one has no direction to either
  // neighbour, nor a chord.
  const sm::Points repeated = {{3.0, 1.0}, {3.5, 1.0}, {3.5, 1.0}, {3.5, 1.0}, {4.0, 1.0}};
  const auto r = sm::scan_normals(repeated, kLaser, beam_normals_on());
  EXPECT_EQ(r.has_normal[2], 0);
  for (const auto& n : r.normals) EXPECT_TRUE(n.allFinite());

  // Collinear, but a neighbour beyond max_gap_m.
  const sm::Points gap = {{3.0, 1.0}, {3.5, 1.0}, {5.0, 1.0}};
  EXPECT_EQ(sm::scan_normals(gap, kLaser, beam_normals_on()).has_normal[1], 0);
}

TEST(ScanNormals, DenseSurfacesKeepTheirNeighboursNormal)
{
  // A wall 1 m ahead sampled every 5 cm: its neighbours give the normal, beam normals or not.
  sm::Points wall;
  for (int i = 0; i <= 20; ++i) wall.emplace_back(1.0, -0.5 + 0.05 * i);
  const auto without = sm::scan_normals(wall, kLaser, sm::ScanNormalOptions{});
  const auto with = sm::scan_normals(wall, kLaser, beam_normals_on());
  for (size_t i = 0; i < wall.size(); ++i) {
    ASSERT_TRUE(without.has_normal[i]) << i;
    EXPECT_EQ(with.normals[i], without.normals[i]) << i;
    EXPECT_NEAR(with.normals[i].x(), -1.0, 1e-9) << i;
  }
}
