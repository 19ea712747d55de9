#include "segmentation_diagnosis.h"

#include <gtest/gtest.h>

namespace rgnav::rgmap_pipeline {
namespace {

using Eigen::Vector2d;

TEST(SegmentationDiagnosis, SplitsThePrecisionLossBySeenAndDrivenThrough)
{
  // Rooms 1 | 2 | 3 side by side, 10 x 10 cells of 1 m each; a wall column (label 0) at x = 10.
  LabelGrid g(32, 10, 1.0, Vector2d(0, 0));
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 32; ++x) g.at(x, y) = x < 10 ? 1 : x == 10 ? 0 : x < 21 ? 2 : 3;
  auto cells = [&](int x0, int x1) {
    std::vector<int64_t> c;
    for (int y = 0; y < 10; ++y)
      for (int x = x0; x < x1; ++x) c.push_back(static_cast<int64_t>(y) * g.width + x);
    return c;
  };
  RegionCells found;
  found[1] = cells(0, 10);                        // room 1 exactly
  found[2] = cells(0, 10);                        // room 1 and a fifth of it again in room 2 ...
  for (int64_t c : cells(11, 13)) found[2].push_back(c);
  found[3] = cells(11, 21);                       // room 2 and ...
  for (int64_t c : cells(21, 26)) found[3].push_back(c);
  std::map<int64_t, std::vector<Vector2d>> positions;
  positions[1] = {Vector2d(5, 5)};
  positions[2] = {Vector2d(5, 5), Vector2d(10.5, 5)};   // on the wall: counts for the nearest room (1 or 2)
  positions[2].push_back(Vector2d(12, 5));              // ... the robot stood in room 2: driven through
  positions[3] = {Vector2d(15, 5)};                     // room 3 only seen

  const auto d = diagnose_segmentation(g, found, positions);
  ASSERT_EQ(d.regions.size(), 3u);
  EXPECT_EQ(d.regions[0].seen_cells + d.regions[0].driven_cells, 0);
  EXPECT_EQ(d.regions[1].best_room, 1);
  EXPECT_EQ(d.regions[1].driven_cells, 20);
  EXPECT_EQ(d.regions[1].seen_cells, 0);
  EXPECT_EQ(d.regions[2].best_room, 2);
  EXPECT_EQ(d.regions[2].seen_cells, 50);
  EXPECT_EQ(d.regions[2].driven_cells, 0);
  // Adds up to 1 - precision (the metric's unweighted mean).
  const double precision = score_segmentation(g, found).precision;
  EXPECT_NEAR(d.seen_loss + d.driven_loss, 1.0 - precision, 1e-12);
  EXPECT_NEAR(d.seen_loss, (50.0 / 150.0) / 3.0, 1e-12);
  // Region 2's robot went from room 1 (twice: the wall position counts for room 1) to room 2.
  const std::vector<std::pair<int32_t, int>> path{{1, 2}, {2, 1}};
  EXPECT_EQ(d.regions[1].path, path);
  const std::string text = to_text(d, {"a", "b", "c"});
  EXPECT_NE(text.find("R3"), std::string::npos);
  EXPECT_NE(text.find("path ax2 bx1"), std::string::npos);
}

}  // namespace
}  // namespace rgnav::rgmap_pipeline
