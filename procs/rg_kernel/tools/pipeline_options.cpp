#include "pipeline_options.h"

#include <cmath>
#include <filesystem>

#include "config/finish_except.h"
#include "gateway_detector/gateway_models.h"
#include "gateway_detector/options.h"
#include "offline_options.h"
#include "procs/rg_kernel/rg_kernel_options.h"

namespace rgnav::rgmap_pipeline {

LoadedPipeline load_pipeline(const PipelineConfigPaths& paths)
{
  LoadedPipeline out;
  auto& o = out.options;
  out.robot = config::load_robot_description_file(paths.robot);
  o.mapper = scan_mapper::load_offline_options(paths.scan_mapper, out.robot);

  const auto gw = config::Config::load(paths.gateway_detector);
  o.detector = gateway_detector::load_detector_options(gw, out.robot);
  const auto cls = gateway_detector::load_classifier_config(gw.section("classifier"), paths.gateway_detector);
  if (!cls.models_path.empty() && std::filesystem::exists(cls.models_path)) {
    auto models = gateway_detector::load_gateway_models(cls.models_path);
    // Same check as the gateway_detector process: features made otherwise than the models were
    // trained on (weights, width, setback, occlusion) would be classified wrongly without any error.
    if (const auto bad = gateway_detector::models_mismatch(models, o.detector.measures))
      gw.section("crossings").fail(bad->key, bad->reason + " (" + cls.models_path + ")");
    out.classifier = std::move(models.classifier);
    out.classifier_note = cls.models_path + " (" + models.description + ")";
  } else if (cls.require_models) {
    gw.section("classifier").fail("models", "file not found: " + cls.models_path);
  } else {
    out.classifier_note = "none (" + (cls.models_path.empty() ? std::string("not configured") : cls.models_path + " missing") +
                          "): crossings classified by their observation weights";
  }
  config::finish_except(gw, {"node", "channels"});

  const auto kernel_cfg = config::Config::load(paths.rg_kernel);
  o.kernel = rg_kernel::load_kernel_options(kernel_cfg, out.robot);
  o.graph = rg_kernel::load_graph_options(kernel_cfg.section("graph"));
  config::finish_except(kernel_cfg, {"node", "channels", "persistence", "publish"});
  return out;
}

}  // namespace rgnav::rgmap_pipeline
