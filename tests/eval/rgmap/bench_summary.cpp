#include "bench_summary.h"

#include <string>

namespace rgnav::rgmap_pipeline {

namespace {

bool ends_with(const std::string& s, const std::string& tail)
{
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

nlohmann::json empty_group(double voronoi_recall, double voronoi_precision)
{
  return {{"worlds", 0},
          {"failed", 0},
          {"seg_precision_mean", nullptr},
          {"seg_recall_mean", nullptr},
          {"gateways_matched", 0},
          {"gateways_truth", 0},
          {"gateways_false", 0},
          {"graph_isomorphic", 0},
          {"reference",
           {{"method", "Voronoi segmentation, Bormann et al. 2016 (offline)"},
            {"seg_recall", voronoi_recall},
            {"seg_precision", voronoi_precision}}}};
}

}  // namespace

nlohmann::json summarize_ipa_worlds(const nlohmann::json& section)
{
  nlohmann::json out = {{"ipa_plain", empty_group(0.950, 0.948)}, {"ipa_furnished", empty_group(0.866, 0.945)}};
  struct Sum
  {
    double precision = 0.0, recall = 0.0;
    int n = 0;
  } sums[2];
  for (const auto& [name, w] : section.items()) {
    const std::string path = w.value("world", "");
    if (!ends_with(path, ".png")) continue;   // the office world and other YAML worlds: no published figures
    const bool furnished = path.find("_furnitures") != std::string::npos;
    auto& g = out[furnished ? "ipa_furnished" : "ipa_plain"];
    g["worlds"] = g["worlds"].get<int>() + 1;
    if (w.contains("error")) {
      g["failed"] = g["failed"].get<int>() + 1;
      continue;
    }
    Sum& s = sums[furnished ? 1 : 0];
    s.precision += w.value("seg_precision", 0.0);
    s.recall += w.value("seg_recall", 0.0);
    ++s.n;
    for (const char* key : {"gateways_matched", "gateways_truth", "gateways_false"})
      g[key] = g[key].get<int>() + w.value(key, 0);
    if (w.value("graph_isomorphic", false)) g["graph_isomorphic"] = g["graph_isomorphic"].get<int>() + 1;
  }
  for (int k = 0; k < 2; ++k) {
    if (sums[k].n == 0) continue;
    auto& g = out[k == 1 ? "ipa_furnished" : "ipa_plain"];
    g["seg_precision_mean"] = sums[k].precision / sums[k].n;
    g["seg_recall_mean"] = sums[k].recall / sums[k].n;
  }
  return out;
}

}  // namespace rgnav::rgmap_pipeline
