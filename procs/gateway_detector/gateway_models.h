// Trained gateway HMMs on disk (config/gateway_models/*.yaml), written by the trainer and
// loaded at start like a config: unknown keys, wrong sizes, non-stochastic matrices or
// covariances that are not positive definite stop the process with the file and key named.
#pragma once

#include <optional>
#include <string>

#include "gateway_detector/classifiers.h"

namespace rgnav::gateway_detector {

struct GatewayModels
{
  std::string description;     // what the models were trained on
  double hallway_width = 0.0;  // [m] d_hw of the measures the features were made with
  double f_vlm = 0.0;          // weights the features were made with (must match the detector)
  double f_gw = 0.0;
  bool exclude_occluded = false;  // MeasureOptions::exclude_occluded of the features
  double over_line_setback = 0.25;  // [m] MeasureOptions::over_line_setback of the features
  HmmClassifier classifier;
};

// Why features made with `measures` would not be what these models were trained on (weights,
// hallway width, Over Line setback, occlusion handling), naming the detector config key; nullopt if they match.
struct ModelsMismatch
{
  std::string key;
  std::string reason;
};
std::optional<ModelsMismatch> models_mismatch(const GatewayModels& models, const MeasureOptions& measures);

// Throws config::ConfigError.
GatewayModels load_gateway_models(const std::string& path);
// Throws std::runtime_error if the file cannot be written (written to a temp file, renamed).
void save_gateway_models(const GatewayModels& models, const std::string& path);

}  // namespace rgnav::gateway_detector
