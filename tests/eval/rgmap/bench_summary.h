// Means over the IPA building maps of a bench section (worlds / worlds_true_poses), plain and
// furnished apart, beside the best published offline method: Bormann et al. 2016 report their
// figures as means over all their maps, so a single map cannot be held against them.
#pragma once

#include <nlohmann/json.hpp>

namespace rgnav::rgmap_pipeline {

// section: name -> the bench's per-world JSON (with "world": the map path, or "error").
// Returns {"ipa_plain": {...}, "ipa_furnished": {...}}: worlds, failed (runs with an error,
// left out of the means), seg_precision_mean, seg_recall_mean, gateways_matched / _truth /
// _false (sums), graph_isomorphic (count) and reference (Voronoi segmentation's figures).
nlohmann::json summarize_ipa_worlds(const nlohmann::json& section);

}  // namespace rgnav::rgmap_pipeline
