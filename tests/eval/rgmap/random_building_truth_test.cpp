// The RG map bench on generated buildings (tests/eval/buildings): its ground truth, read from the
// written images as for the IPA maps, has one room per generated room and one gateway per
// doorway between the rooms the doorway joins; and its summary keeps the generated buildings
// apart from the IPA maps with the failure ratios of issue 33.
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <set>

#include <unistd.h>

#include "bench_summary.h"
#include "building_files.h"
#include "ground_truth.h"
#include "sim/world_yaml.h"

namespace rgnav::rgmap_pipeline {
namespace {

namespace rb = rgnav::buildings;

// Known losses of the bench's truth on these maps (to fix in ground_truth.cpp / the loader, not
// here): the loader fits straight outlines to the rooms (sim::rooms_from_segmentation,
// approxPolyDP) and a bump of wall noise can move an outline a pixel into the room, while the
// truth's doorway runs look only 2 px either side for rooms, so a doorway in such a wall is
// missed; and a ring hallway's outline is its outer contour, which covers the block inside it, so
// a doorway between two rooms of that block can be put between the hallway and one of them.
// Both must stay rare (seeds 1-30: 26 of 994 doorways not in the truth as made, 16 of them put
// between other rooms): no building has more truth gateways than doorways.
TEST(RandomBuildingTruth, GatewaysAreTheDoorwaysBetweenTheirRooms)
{
  const auto dir = std::filesystem::temp_directory_path() / ("rgnav_rgmap_truth_test_" + std::to_string(::getpid()));
  int doorways = 0, missed = 0, wrong = 0;
  for (uint64_t seed = 1; seed <= 30; ++seed) {
    const auto b = rb::generate_building(seed);
    const auto im = rb::render_building(b);
    rb::write_building(b, im, dir.string());
    for (const std::string variant : {"", "_furnitures"}) {
      const auto world = sim::load_world((dir / (rb::building_stem(seed) + variant + ".png")).string());
      const auto truth = ground_truth_of(world);
      ASSERT_EQ(truth.room_names.size(), b.spaces.size()) << seed << variant;
      // The generator's room pairs, in the loader's labels (label at a pixel of each room).
      auto label_of_space = [&](int space) {
        const auto& r = b.spaces[static_cast<size_t>(space)].rects[0];
        const Eigen::Vector2d centre((r.x0 + r.x1) * 0.5 * 0.05, (b.height - (r.y0 + r.y1) * 0.5) * 0.05);
        const Eigen::Vector2i cell = ((centre - truth.rooms.origin) / truth.rooms.resolution).cast<int>();
        return truth.rooms.at(cell.x(), cell.y());
      };
      std::multiset<std::pair<int32_t, int32_t>> want;
      for (const auto& d : b.doorways) {
        const int32_t la = label_of_space(d.a), lb = label_of_space(d.b);
        want.insert({std::min(la, lb), std::max(la, lb)});
      }
      for (const auto& g : truth.gateways) {
        const auto it = want.find({g.rooms.at(0), g.rooms.at(1)});
        if (it == want.end()) {
          ++wrong;
          continue;
        }
        want.erase(it);
      }
      doorways += static_cast<int>(b.doorways.size());
      missed += static_cast<int>(want.size());
      EXPECT_LE(truth.gateways.size(), b.doorways.size()) << seed << variant;
    }
  }
  EXPECT_LE(missed, doorways / 25) << missed << " of " << doorways << " doorways missing from the truth";
  EXPECT_LE(wrong, doorways / 25) << wrong << " of " << doorways << " doorways between the wrong rooms in the truth";
  std::cerr << "doorways " << doorways << ", missed " << missed << ", between other rooms " << wrong << "\n";
  std::filesystem::remove_all(dir);
}

TEST(RandomBuildingSummary, GroupsAndRatios)
{
  const nlohmann::json section = {
      {"ipa", {{"world", "ipa/a.png"}, {"seg_precision", 0.9}, {"seg_recall", 1.0}, {"gateways_crossed", 4},
               {"gateways_crossed_matched", 3}, {"gateways_matched", 3}, {"gateways_false", 1}, {"graph_isomorphic", true}}},
      {"rand_1", {{"world", "r/rand_1.png"}, {"random_building", true}, {"seg_precision", 0.8}, {"seg_recall", 0.9},
                  {"gateways_crossed", 10}, {"gateways_crossed_matched", 9}, {"gateways_matched", 9}, {"gateways_false", 3},
                  {"graph_isomorphic", true}, {"alignment_rmse_m", 0.05}}},
      {"rand_2", {{"world", "r/rand_2.png"}, {"random_building", true}, {"seg_precision", 0.6}, {"seg_recall", 0.7},
                  {"gateways_crossed", 10}, {"gateways_crossed_matched", 6}, {"gateways_matched", 6}, {"gateways_false", 0},
                  {"graph_isomorphic", false}, {"alignment_rmse_m", 0.9}}},
      {"rand_2_furnished", {{"world", "r/rand_2_furnitures.png"}, {"random_building", true}, {"error", "no tour"}}}};
  const auto s = summarize_ipa_worlds(section);
  const auto& plain = s["random_plain"];
  EXPECT_EQ(plain["worlds"], 2);
  EXPECT_NEAR(plain["seg_precision_mean"].get<double>(), 0.7, 1e-12);
  EXPECT_NEAR(plain["doorways_crossed_gateway_ratio"].get<double>(), 15.0 / 20.0, 1e-12);
  EXPECT_NEAR(plain["false_gateway_ratio"].get<double>(), 3.0 / 18.0, 1e-12);
  EXPECT_NEAR(plain["isomorphic_ratio"].get<double>(), 0.5, 1e-12);
  EXPECT_EQ(plain["broken_maps"], 1);
  EXPECT_FALSE(plain.contains("reference"));
  EXPECT_EQ(s["random_furnished"]["failed"], 1);
  EXPECT_TRUE(s["random_furnished"]["isomorphic_ratio"].is_null());
  EXPECT_EQ(s["ipa_plain"]["worlds"], 1);   // the IPA means leave the generated buildings out
  EXPECT_NEAR(s["ipa_plain"]["doorways_crossed_gateway_ratio"].get<double>(), 0.75, 1e-12);
  EXPECT_EQ(broken_maps(section), (nlohmann::json{{"rand_2", 0.9}}));
}

}  // namespace
}  // namespace rgnav::rgmap_pipeline
