#include "training.h"

#include <spdlog/spdlog.h>

#include <stdexcept>

#include "config/finish_except.h"
#include "gateway_detector/options.h"
#include "sim/world_yaml.h"

namespace rgnav::gateway_detector::tools {

TrainingConfig load_training_config(const std::string& path)
{
  const auto cfg = config::Config::load(path);
  TrainingConfig t;
  const auto envs = cfg.section("environments");
  for (const auto& name : envs.keys()) {
    const auto e = envs.section(name);
    t.environments.push_back({name, e.string("paper", "")});
    try {
      width_of_environment(name);
    } catch (const std::exception&) {
      envs.fail(name, "not a hallway world (hallways_<w>m_<clutter>)");
    }
  }
  if (t.environments.empty()) cfg.fail("environments", "needs at least one world");
  t.office_world = cfg.string("office_world", t.office_world);
  const auto rec = cfg.section("record");
  auto& r = t.record;
  r.repetitions = static_cast<int>(rec.integer("repetitions", r.repetitions, 2, 1000));
  r.approach_length = rec.number("approach_length_m", r.approach_length, 3.0, 20.0);
  r.lateral_fraction = rec.number("lateral_fraction", r.lateral_fraction, 0.0, 0.4);
  r.heading_noise = rec.number("heading_noise_rad", r.heading_noise, 0.0, 0.3);
  r.speed = rec.number("speed_mps", r.speed, 0.1, 0.9);
  r.scan_hz = rec.number("scan_hz", r.scan_hz, 1.0, 75.0);
  r.match_fraction = rec.number("match_fraction", r.match_fraction, 0.05, 1.0);
  r.complete_only = rec.boolean("complete_only", r.complete_only);
  r.seed = static_cast<uint64_t>(rec.integer("seed", 1, 1, 1'000'000'000));
  const std::string features = cfg.string("features", hmm_features_name(t.features));
  const auto f = hmm_features_from_name(features);
  if (!f) cfg.fail("features", "must be weights or measures");
  t.features = *f;
  t.hmm = load_training_options(cfg.section("hmm"));
  cfg.finish();
  return t;
}

std::vector<LabelledSequence> record_environment(const std::string& world_name, const DetectorOptions& base,
                                                 const RecordOptions& record, const std::string& worlds_dir,
                                                 double* width, RecordStats* stats)
{
  const double w = width_of_environment(world_name);
  if (width) *width = w;
  DetectorOptions o = base;
  o.vlm.hallway_width = o.measures.hallway_width = w;
  const auto world = sim::load_world(sim::resolve_world_path(world_name, worlds_dir));
  return record_sequences(world, o, record, stats);
}

double width_of_environment(const std::string& name)
{
  const std::string prefix = "hallways_";
  const auto m = name.find("m_");
  if (name.rfind(prefix, 0) != 0 || m == std::string::npos) throw std::invalid_argument("not a hallway world: " + name);
  return std::stod(name.substr(prefix.size(), m - prefix.size()));
}

HmmClassifier train_classifier(const std::vector<LabelledSequence>& sequences, const HmmTrainingOptions& options,
                               HmmFeatures features)
{
  HmmClassifier c(features);
  for (int cls = 0; cls < kNumSequenceClasses; ++cls) {
    std::vector<TrainingSequence> data;
    for (const auto& s : sequences) {
      if (s.cls != cls) continue;
      TrainingSequence t;
      for (const auto& o : s.sequence) t.push_back({feature_vector(o, features), o.distance});
      data.push_back(std::move(t));
    }
    if (data.size() < 2) continue;
    c.models()[static_cast<size_t>(cls)] = train_hmm(data, options);
  }
  return c;
}

DetectorOptions load_detector_config(const std::string& config_dir)
{
  const auto cfg = config::Config::load(config_dir + "/gateway_detector.yaml");
  const DetectorOptions options = load_detector_options(cfg, config::load_robot_description_file(config_dir + "/robot.yaml"));
  config::finish_except(cfg, {"node", "channels", "classifier"});
  return options;
}

int run_tool(const std::function<int()>& body)
{
  try {
    return body();
  } catch (const config::ConfigError& e) {
    spdlog::critical("{}", e.what());
    return 2;
  } catch (const std::exception& e) {
    spdlog::critical("{}", e.what());
    return 1;
  }
}

}  // namespace rgnav::gateway_detector::tools
