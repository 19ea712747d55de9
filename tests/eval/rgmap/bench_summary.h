// Means over the building maps of a bench section (worlds / worlds_true_poses): the IPA maps
// beside the best published offline method (Bormann et al. 2016 report their figures as means
// over all their maps, so a single map cannot be held against them), and the random buildings
// (tests/eval/buildings, marked "random_building" by the bench), plain and furnished apart.
#pragma once

#include <nlohmann/json.hpp>

namespace rgnav::rgmap_pipeline {

// A map whose accepted scans fit their true poses, after the best rigid fit, with a larger RMSE
// than this is broken (issue 33): walls doubled, a hallway bent.
constexpr double kBrokenMapRmseM = 0.3;

// section: name -> the bench's per-world JSON (with "world": the map path, or "error").
// Returns {"ipa_plain", "ipa_furnished", "random_plain", "random_furnished"}, each: worlds, failed
// (runs with an error, left out of the means), seg_precision_mean, seg_recall_mean,
// gateways_matched / _truth / _false, gateways_crossed / _crossed_matched (sums), graph_isomorphic
// (count), broken_maps (alignment_rmse_m > kBrokenMapRmseM), and the ratios
// doorways_crossed_gateway_ratio (crossed doorways that became gateways / crossed doorways),
// false_gateway_ratio (false / reported gateways), isomorphic_ratio (isomorphic / worlds run);
// the IPA groups also reference (Voronoi segmentation's figures). YAML worlds are left out.
nlohmann::json summarize_ipa_worlds(const nlohmann::json& section);

// Worlds of a section with alignment_rmse_m > kBrokenMapRmseM: name -> RMSE.
nlohmann::json broken_maps(const nlohmann::json& section);

}  // namespace rgnav::rgmap_pipeline
