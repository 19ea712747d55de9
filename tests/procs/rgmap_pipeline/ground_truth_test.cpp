// Ground truth from an IPA-style map pair made by hand: two rooms joined by one doorway.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>

#include "ground_truth.h"
#include "sim/world_yaml.h"

namespace rgnav::rgmap_pipeline {
namespace {

using Eigen::Vector2d;
namespace fs = std::filesystem;

// 100 x 60 pixels at 5 cm: a 1-pixel black border, a wall at column 50 with a doorway in rows
// 25..40 (0.8 m); the segmentation image closes the doorway.
class TwoRooms : public ::testing::Test
{
 protected:
  void SetUp() override
  {
    dir_ = fs::temp_directory_path() / ("rgmap_gt_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    cv::Mat map(60, 100, CV_8U, cv::Scalar(255));
    map.row(0).setTo(0), map.row(59).setTo(0), map.col(0).setTo(0), map.col(99).setTo(0);
    map.col(50).setTo(0);
    map(cv::Range(25, 41), cv::Range(50, 51)).setTo(255);
    cv::Mat seg = map.clone();
    seg(cv::Range(25, 41), cv::Range(50, 51)).setTo(0);
    ASSERT_TRUE(cv::imwrite((dir_ / "two.png").string(), map));
    ASSERT_TRUE(cv::imwrite((dir_ / "two_gt_segmentation.png").string(), seg));
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(TwoRooms, RoomsGatewayAndGraph)
{
  const auto world = sim::load_world((dir_ / "two.png").string());
  ASSERT_EQ(world.regions.size(), 2u);
  const auto t = ground_truth_of(world);
  ASSERT_EQ(t.room_names.size(), 2u);
  // Each room's cells: 49 x 58 pixels, up to the polygon rasterisation at the border.
  int n1 = 0, n2 = 0;
  for (int32_t l : t.rooms.labels) n1 += l == 1, n2 += l == 2;
  EXPECT_NEAR(n1, 49 * 58, 49 * 58 * 0.1);
  EXPECT_NEAR(n2, 49 * 58, 49 * 58 * 0.1);
  ASSERT_EQ(t.gateways.size(), 1u);
  const auto& g = t.gateways[0];
  EXPECT_EQ(g.rooms, (std::vector<int32_t>{1, 2}));
  ASSERT_EQ(g.points.size(), 2u);
  EXPECT_NEAR(g.center().x(), 50.5 * 0.05, 1e-6);
  EXPECT_NEAR(g.center().y(), (60 - 32.5 - 0.5) * 0.05, 1e-6);
  EXPECT_NEAR((g.points[1] - g.points[0]).norm(), 0.8, 0.06);

  const Graph graph = truth_graph(t, {1, 2});
  EXPECT_EQ(graph.edges.size(), 1u);
  EXPECT_TRUE(truth_graph(t, {1}).edges.empty());

  const double yd = g.center().y();
  EXPECT_EQ(crossed_gateways(t, {Vector2d(1, yd), Vector2d(4, yd)}).size(), 1u);
  EXPECT_TRUE(crossed_gateways(t, {Vector2d(1, 0.3), Vector2d(4, 0.3)}).empty());   // through the wall
  EXPECT_TRUE(crossed_gateways(t, {Vector2d(1, yd), Vector2d(2, yd)}).empty());     // stays in room 1
}

}  // namespace
}  // namespace rgnav::rgmap_pipeline

namespace rgnav::rgmap_pipeline {
namespace {

TEST(OfficeWorld, LabelledGatewaysAndTheCrossingBetweenFourHallways)
{
  const auto world = sim::load_world(std::string(RGNAV_CONFIG_DIR) + "/worlds/office.yaml");
  const auto t = ground_truth_of(world, 0.1);
  ASSERT_EQ(t.room_names.size(), world.regions.size());
  const int32_t west = t.label_of("hall_a_west"), east = t.label_of("hall_a_east");
  const int32_t south = t.label_of("hall_b_south"), north = t.label_of("hall_b_north");
  ASSERT_GT(west, 0);
  ASSERT_GT(east, 0);
  bool crossing = false, dead_end = false;
  for (const auto& g : t.gateways) {
    if (g.name == "crossing_ab") {
      crossing = true;
      // The crossing square is in no room: its rooms are the four hallways it joins.
      EXPECT_EQ(g.rooms, (std::vector<int32_t>{south, north, west, east}));
      EXPECT_NEAR(g.center().x(), 20, 1e-9);
      EXPECT_NEAR(g.center().y(), 13, 1e-9);
    }
    if (g.name == "dead_end_a_west") {
      dead_end = true;
      EXPECT_EQ(g.rooms, (std::vector<int32_t>{west}));
    }
  }
  EXPECT_TRUE(crossing);
  EXPECT_TRUE(dead_end);
  // A point in a labelled office is labelled with that office.
  const int32_t w1 = t.label_of("office_w1");
  const auto& g = t.rooms;
  const int cx = static_cast<int>((5.0 - g.origin.x()) / g.resolution), cy = static_cast<int>((9.0 - g.origin.y()) / g.resolution);
  EXPECT_EQ(g.at(cx, cy), w1);
  // All rooms: the graph is connected through the hallways and has the hallway loop.
  std::vector<int32_t> all;
  for (size_t k = 1; k <= t.room_names.size(); ++k) all.push_back(static_cast<int32_t>(k));
  const Graph graph = truth_graph(t, all);
  EXPECT_EQ(graph.nodes.size(), t.room_names.size());
  EXPECT_GT(graph.edges.size(), graph.nodes.size() - 1);
  EXPECT_TRUE(graph.edges.count({std::min(west, north), std::max(west, north)}));
  EXPECT_TRUE(graph.edges.count({std::min(west, east), std::max(west, east)}));
}

}  // namespace
}  // namespace rgnav::rgmap_pipeline
