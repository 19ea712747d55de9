// Loading and validating the detector's options from config/gateway_detector.yaml (every
// value range-checked; unknown keys are refused by Config::finish in process_main).
#pragma once

#include <string>

#include "config/config.h"
#include "config/robot_description.h"
#include "gateway_detector/gateway_detector.h"
#include "gateway_detector/hmm.h"

namespace rgnav::gateway_detector {

// Reads sections features, crossings, narrow_passages, doors, tracking of `cfg`; the robot
// radius (narrow passages: D_lr^min) is the robot description's.
DetectorOptions load_detector_options(const config::Config& cfg, const config::RobotDescription& robot);
HmmTrainingOptions load_training_options(const config::Config& section);

// The `classifier:` section: where the trained models are (relative paths resolve against
// the directory of the config file) and whether running without them is allowed.
struct ClassifierConfig
{
  std::string models_path;   // "" = none
  bool require_models = false;
};
ClassifierConfig load_classifier_config(const config::Config& section, const std::string& config_path);

}  // namespace rgnav::gateway_detector
