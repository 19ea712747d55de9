// gateway_trainer: records labelled observation sequences in the simulated hallway worlds and
// writes one set of gateway HMMs per hallway width to config/gateway_models/ (diss. 4.1.3.3),
// plus default.yaml for the width in config/gateway_detector.yaml.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <map>
#include <sstream>

#include "gateway_detector/gateway_models.h"
#include "gateway_detector/options.h"
#include "runtime/process_main.h"
#include "training.h"

using namespace rgnav;
using namespace rgnav::gateway_detector;

int main(int argc, char** argv)
{
  CLI::App app{"Train the gateway HMMs on the simulated hallway worlds"};
  std::string config_dir = runtime::default_config_dir();
  int repetitions = 0;
  std::vector<std::string> only;
  app.add_option("--config-dir", config_dir, "rgnav config directory (gateway_detector.yaml, gateway_models/, worlds/)");
  app.add_option("--repetitions", repetitions, "runs per approach (default: training.yaml)");
  app.add_option("--only", only, "train only these environments");
  CLI11_PARSE(app, argc, argv);
  return tools::run_tool([&] {
    const std::string models_dir = config_dir + "/gateway_models";
    auto training = tools::load_training_config(models_dir + "/training.yaml");
    if (repetitions > 0) training.record.repetitions = repetitions;
    const DetectorOptions base = tools::load_detector_config(config_dir);

    std::map<double, std::vector<tools::LabelledSequence>> by_width;
    for (const auto& env : training.environments) {
      if (!only.empty() && std::find(only.begin(), only.end(), env.world) == only.end()) continue;
      double w = 0.0;
      tools::RecordStats stats;
      auto seqs = tools::record_environment(env.world, base, training.record, config_dir + "/worlds", &w, &stats);
      spdlog::info("{}: {} runs, {} labelled sequences ({} unmatched)", env.world, stats.runs, seqs.size(), stats.sequences_unmatched);
      auto& all = by_width[w];
      all.insert(all.end(), std::make_move_iterator(seqs.begin()), std::make_move_iterator(seqs.end()));
    }
    if (by_width.empty()) throw std::runtime_error("no environment selected");
    for (const auto& [w, seqs] : by_width) {
      GatewayModels m;
      std::ostringstream desc;
      desc << seqs.size() << " sequences from the " << w << " m hallway worlds, seed " << training.record.seed;
      m.description = desc.str();
      m.hallway_width = w;
      m.f_vlm = base.measures.f_vlm;
      m.f_gw = base.measures.f_gw;
      m.exclude_occluded = base.measures.exclude_occluded;
      m.over_line_setback = base.measures.over_line_setback;
      m.classifier = tools::train_classifier(seqs, training.hmm, training.features);
      std::ostringstream name;
      name << "hallways_" << w << "m.yaml";
      save_gateway_models(m, models_dir + "/" + name.str());
      spdlog::info("wrote {}/{}", models_dir, name.str());
      if (std::fabs(w - base.measures.hallway_width) < 1e-9) {
        save_gateway_models(m, models_dir + "/default.yaml");
        spdlog::info("wrote {}/default.yaml (hallway width {} m, as gateway_detector.yaml)", models_dir, w);
      }
    }
    return 0;
  });
}
