// gateway_detector: narrow passages, doors and crossing gateways from laser scans (diss. ch. 4).
#include <cmath>
#include <filesystem>
#include <memory>

#include <spdlog/spdlog.h>

#include "gateway_detector/gateway_detector_node.h"
#include "gateway_detector/gateway_models.h"
#include "gateway_detector/options.h"
#include "runtime/process_main.h"

using namespace rgnav;
using namespace rgnav::gateway_detector;

int main(int argc, char** argv)
{
  return runtime::process_main(argc, argv, "gateway_detector", [](runtime::ProcessContext& ctx) {
    const auto& cfg = ctx.config;
    const DetectorOptions options = load_detector_options(cfg, ctx.robot);
    const auto classifier_cfg = load_classifier_config(cfg.section("classifier"), ctx.config_path);
    HmmClassifier classifier;
    if (!classifier_cfg.models_path.empty() && std::filesystem::exists(classifier_cfg.models_path)) {
      auto models = load_gateway_models(classifier_cfg.models_path);
      if (const auto bad = models_mismatch(models, options.measures))
        cfg.section("crossings").fail(bad->key, bad->reason + " (" + classifier_cfg.models_path + ")");
      classifier = std::move(models.classifier);
      spdlog::info("gateway HMMs from {} ({})", classifier_cfg.models_path, models.description);
    } else if (classifier_cfg.require_models) {
      cfg.section("classifier").fail("models", "file not found: " + classifier_cfg.models_path + " (run ./rgnav train-gateways)");
    } else {
      spdlog::warn("no gateway HMMs ({}): crossings are classified by their observation weights",
                   classifier_cfg.models_path.empty() ? "none configured" : classifier_cfg.models_path + " missing");
    }
    return std::make_shared<GatewayDetectorNode>(ctx.node, GatewayDetector(options, std::move(classifier)),
                                                 load_node_channels(cfg.section("channels")),
                                                 ctx.robot.laser_front.base_from_laser);
  });
}
