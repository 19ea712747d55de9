// What the trainer and the benchmark share: config/gateway_models/training.yaml (worlds,
// recording and HMM options) and training one HMM per class from labelled sequences.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "config/config.h"
#include "gateway_detector/classifiers.h"
#include "gateway_detector/gateway_detector.h"
#include "gateway_detector/hmm.h"
#include "sim_runs.h"

namespace rgnav::gateway_detector::tools {

struct TrainingConfig
{
  struct Environment
  {
    std::string world;   // name under config/worlds
    std::string paper;   // the dissertation's name for the comparable environment ("" = none)
  };
  std::vector<Environment> environments;
  std::string office_world = "office";    // door evaluation
  RecordOptions record;
  HmmFeatures features = HmmFeatures::kWeights;  // what the HMMs observe
  HmmTrainingOptions hmm;
};
TrainingConfig load_training_config(const std::string& path);

// The detector's options from CONFIG_DIR/gateway_detector.yaml, read by the gateway_detector
// process's own loader with its unknown-key check (its node, channels, laser mount and
// classifier sections aside: training and the benchmark make their own models).
DetectorOptions load_detector_config(const std::string& config_dir);

// Hallway width of a hallway world from its name (hallways_2.5m_... -> 2.5); throws otherwise.
double width_of_environment(const std::string& name);

// The labelled sequences of one hallway environment (a world under `worlds_dir`), recorded with
// `base` tuned to the environment's hallway width, which is returned in `width` (unless null).
std::vector<LabelledSequence> record_environment(const std::string& world_name, const DetectorOptions& base,
                                                 const RecordOptions& record, const std::string& worlds_dir,
                                                 double* width, RecordStats* stats);

// One HMM per sequence class that has at least two sequences.
HmmClassifier train_classifier(const std::vector<LabelledSequence>& sequences, const HmmTrainingOptions& options,
                               HmmFeatures features);

// Runs the body of a tool's main(): its exit code, or, logged, 2 on a configuration error and 1
// on any other error.
int run_tool(const std::function<int()>& body);

}  // namespace rgnav::gateway_detector::tools
