#include "bench_summary.h"

#include <gtest/gtest.h>

namespace rgnav::rgmap_pipeline {
namespace {

TEST(BenchSummary, MeansOverIpaMapsPlainAndFurnishedApartLeavingOutFailuresAndYamlWorlds)
{
  const nlohmann::json section = {
      {"office", {{"world", "config/worlds/office.yaml"}, {"seg_precision", 0.1}, {"seg_recall", 0.1}}},
      {"a", {{"world", "ipa/a.png"}, {"seg_precision", 0.9}, {"seg_recall", 1.0}, {"gateways_matched", 3},
             {"gateways_truth", 4}, {"gateways_false", 1}, {"graph_isomorphic", true}}},
      {"b", {{"world", "ipa/b_scan.png"}, {"seg_precision", 0.7}, {"seg_recall", 0.8}, {"gateways_matched", 2},
             {"gateways_truth", 5}, {"gateways_false", 0}, {"graph_isomorphic", false}}},
      {"b_furnished", {{"world", "ipa/b_scan_furnitures.png"}, {"error", "no tour through this world"}}},
      {"a_furnished", {{"world", "ipa/a_furnitures.png"}, {"seg_precision", 0.5}, {"seg_recall", 0.6}}}};
  const auto s = summarize_ipa_worlds(section);
  const auto& plain = s["ipa_plain"];
  EXPECT_EQ(plain["worlds"], 2);
  EXPECT_EQ(plain["failed"], 0);
  EXPECT_NEAR(plain["seg_precision_mean"].get<double>(), 0.8, 1e-12);
  EXPECT_NEAR(plain["seg_recall_mean"].get<double>(), 0.9, 1e-12);
  EXPECT_EQ(plain["gateways_matched"], 5);
  EXPECT_EQ(plain["gateways_truth"], 9);
  EXPECT_EQ(plain["gateways_false"], 1);
  EXPECT_EQ(plain["graph_isomorphic"], 1);
  EXPECT_DOUBLE_EQ(plain["reference"]["seg_precision"].get<double>(), 0.948);
  const auto& furnished = s["ipa_furnished"];
  EXPECT_EQ(furnished["worlds"], 2);
  EXPECT_EQ(furnished["failed"], 1);
  EXPECT_NEAR(furnished["seg_precision_mean"].get<double>(), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(furnished["reference"]["seg_recall"].get<double>(), 0.866);
}

TEST(BenchSummary, NoMapsNoMeans)
{
  const auto s = summarize_ipa_worlds(nlohmann::json::object());
  EXPECT_TRUE(s["ipa_plain"]["seg_precision_mean"].is_null());
  EXPECT_EQ(s["ipa_furnished"]["worlds"], 0);
}

}  // namespace
}  // namespace rgnav::rgmap_pipeline
