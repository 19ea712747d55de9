#include "bench_summary.h"

#include <map>
#include <string>

namespace rgnav::rgmap_pipeline {

namespace {

bool ends_with(const std::string& s, const std::string& tail)
{
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

nlohmann::json empty_group()
{
  return {{"worlds", 0},
          {"failed", 0},
          {"seg_precision_mean", nullptr},
          {"seg_recall_mean", nullptr},
          {"gateways_matched", 0},
          {"gateways_truth", 0},
          {"gateways_false", 0},
          {"gateways_crossed", 0},
          {"gateways_crossed_matched", 0},
          {"graph_isomorphic", 0},
          {"broken_maps", 0}};
}

nlohmann::json ipa_group(double voronoi_recall, double voronoi_precision)
{
  auto g = empty_group();
  g["reference"] = {{"method", "Voronoi segmentation, Bormann et al. 2016 (offline)"},
                    {"seg_recall", voronoi_recall},
                    {"seg_precision", voronoi_precision}};
  return g;
}

// part / whole, null when there is no whole.
nlohmann::json ratio(int part, int whole) { return whole > 0 ? nlohmann::json(static_cast<double>(part) / whole) : nlohmann::json(nullptr); }

}  // namespace

nlohmann::json summarize_ipa_worlds(const nlohmann::json& section)
{
  nlohmann::json out = {{"ipa_plain", ipa_group(0.950, 0.948)},
                        {"ipa_furnished", ipa_group(0.866, 0.945)},
                        {"random_plain", empty_group()},
                        {"random_furnished", empty_group()}};
  struct Sum
  {
    double precision = 0.0, recall = 0.0;
    int n = 0;
  };
  std::map<std::string, Sum> sums;
  for (const auto& [name, w] : section.items()) {
    const std::string path = w.value("world", "");
    if (!ends_with(path, ".png")) continue;   // the office world and other YAML worlds: no published figures
    const bool furnished = path.find("_furnitures") != std::string::npos;
    const std::string group = std::string(w.value("random_building", false) ? "random_" : "ipa_") + (furnished ? "furnished" : "plain");
    auto& g = out[group];
    g["worlds"] = g["worlds"].get<int>() + 1;
    if (w.contains("error")) {
      g["failed"] = g["failed"].get<int>() + 1;
      continue;
    }
    Sum& s = sums[group];
    s.precision += w.value("seg_precision", 0.0);
    s.recall += w.value("seg_recall", 0.0);
    ++s.n;
    for (const char* key : {"gateways_matched", "gateways_truth", "gateways_false", "gateways_crossed", "gateways_crossed_matched"})
      g[key] = g[key].get<int>() + w.value(key, 0);
    if (w.value("graph_isomorphic", false)) g["graph_isomorphic"] = g["graph_isomorphic"].get<int>() + 1;
    if (w.value("alignment_rmse_m", 0.0) > kBrokenMapRmseM) g["broken_maps"] = g["broken_maps"].get<int>() + 1;
  }
  for (auto& [group, g] : out.items()) {
    const auto s = sums.find(group);
    const int run = s == sums.end() ? 0 : s->second.n;
    if (run > 0) {
      g["seg_precision_mean"] = s->second.precision / run;
      g["seg_recall_mean"] = s->second.recall / run;
    }
    g["doorways_crossed_gateway_ratio"] = ratio(g["gateways_crossed_matched"].get<int>(), g["gateways_crossed"].get<int>());
    const int matched = g["gateways_matched"].get<int>(), wrong = g["gateways_false"].get<int>();
    g["false_gateway_ratio"] = ratio(wrong, matched + wrong);
    g["isomorphic_ratio"] = ratio(g["graph_isomorphic"].get<int>(), run);
  }
  return out;
}

nlohmann::json broken_maps(const nlohmann::json& section)
{
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, w] : section.items())
    if (w.value("alignment_rmse_m", 0.0) > kBrokenMapRmseM) out[name] = w["alignment_rmse_m"];
  return out;
}

}  // namespace rgnav::rgmap_pipeline
