#include "gateway_detector/gateway_models.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "config/config.h"

namespace rgnav::gateway_detector {

namespace {
constexpr const char* kFormat = "rgnav-gateway-hmm-1";

Eigen::MatrixXd as_matrix(const std::vector<double>& v, Eigen::Index rows, Eigen::Index cols)
{
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index r = 0; r < rows; ++r)
    for (Eigen::Index c = 0; c < cols; ++c) m(r, c) = v[static_cast<size_t>(r * cols + c)];
  return m;
}

void emit_numbers(YAML::Emitter& e, const double* p, size_t n)
{
  e << YAML::Flow << YAML::BeginSeq;
  for (size_t i = 0; i < n; ++i) e << p[i];
  e << YAML::EndSeq;
}
}  // namespace

GatewayModels load_gateway_models(const std::string& path)
{
  const auto cfg = config::Config::load(path);
  if (cfg.required_string("format") != kFormat) cfg.fail("format", std::string("must be ") + kFormat);
  GatewayModels m;
  m.description = cfg.string("description", "");
  m.hallway_width = cfg.required_number("hallway_width_m", 0.5, 10.0);
  m.f_vlm = cfg.required_number("f_vlm", 0.0, 100.0);
  m.f_gw = cfg.required_number("f_gw", 0.0, 100.0);
  m.exclude_occluded = cfg.boolean("exclude_occluded", false);
  // Files from before the setback was recorded were trained with 0.25 m.
  m.over_line_setback = cfg.number("over_line_setback_m", 0.25, 0.0, 5.0);
  const std::string features_name = cfg.string("features", hmm_features_name(HmmFeatures::kWeights));
  const auto features = hmm_features_from_name(features_name);
  if (!features) cfg.fail("features", "must be weights or measures");
  m.classifier = HmmClassifier(*features);
  const int fdim = feature_dimension(*features);
  const auto dim = static_cast<Eigen::Index>(cfg.integer("dimension", fdim, fdim, fdim));
  const auto models = cfg.section("models");
  for (const auto& name : models.keys()) {
    const int cls = crossing_class_from_name(name);
    if (cls < 0 || cls >= kNumSequenceClasses) models.fail(name, "not a gateway class with sequences");
    const auto mc = models.section(name);
    const auto states_cfg = mc.list("states");
    const auto q = static_cast<Eigen::Index>(states_cfg.size());
    if (q < 1) mc.fail("states", "needs at least one state");
    const auto prior = mc.numbers("prior", {}, 0.0, 1.0, static_cast<size_t>(q), static_cast<size_t>(q));
    const auto trans = mc.numbers("transition", {}, 0.0, 1.0, static_cast<size_t>(q * q), static_cast<size_t>(q * q));
    std::vector<HmmState> states;
    for (const auto& sc : states_cfg) {
      HmmState s;
      s.distance = sc.number("distance_m", 0.0, 0.0, 100.0);
      s.weights = sc.numbers("weights", {}, 0.0, 1.0, 1, 64);
      const auto comps = sc.list("components");
      if (comps.size() != s.weights.size()) sc.fail("components", "count differs from weights");
      for (const auto& cc : comps) {
        const auto mean = cc.numbers("mean", {}, -1e6, 1e6, static_cast<size_t>(dim), static_cast<size_t>(dim));
        const auto cov = cc.numbers("covariance", {}, -1e6, 1e6, static_cast<size_t>(dim * dim), static_cast<size_t>(dim * dim));
        try {
          s.components.emplace_back(Eigen::Map<const Eigen::VectorXd>(mean.data(), dim), as_matrix(cov, dim, dim));
        } catch (const std::invalid_argument& e) {
          cc.fail("covariance", e.what());
        }
      }
      states.push_back(std::move(s));
    }
    try {
      m.classifier.models()[static_cast<size_t>(cls)].emplace(std::move(states), Eigen::Map<const Eigen::VectorXd>(prior.data(), q),
                                                              as_matrix(trans, q, q));
    } catch (const std::invalid_argument& e) {
      mc.fail("transition", e.what());
    }
  }
  if (m.classifier.empty()) cfg.fail("models", "no class model");
  // A file cut off between two class models is valid YAML with fewer models: the count written
  // with them tells (files written before it was recorded have none).
  if (cfg.has("classes")) {
    const auto written = cfg.integer("classes", 0, 1, kNumSequenceClasses);
    if (written != static_cast<int64_t>(models.keys().size()))
      cfg.fail("classes", "says " + std::to_string(written) + " class models, the file holds " +
                              std::to_string(models.keys().size()) + " (cut off?)");
  }
  cfg.finish();
  return m;
}

std::optional<ModelsMismatch> models_mismatch(const GatewayModels& m, const MeasureOptions& o)
{
  if (std::fabs(m.f_vlm - o.f_vlm) > 1e-9 || std::fabs(m.f_gw - o.f_gw) > 1e-9)
    return ModelsMismatch{"f_vlm", "differs from the weights the models were trained with"};
  if (std::fabs(m.hallway_width - o.hallway_width) > 1e-6)
    return ModelsMismatch{"hallway_width_m", "differs from the " + std::to_string(m.hallway_width) + " m the models were trained for"};
  if (std::fabs(m.over_line_setback - o.over_line_setback) > 1e-9)
    return ModelsMismatch{"over_line_setback_m", "differs from the " + std::to_string(m.over_line_setback) +
                                                     " m the models were trained with"};
  if (m.exclude_occluded != o.exclude_occluded)
    return ModelsMismatch{"exclude_occluded", std::string("the models were trained with exclude_occluded: ") +
                                                  (m.exclude_occluded ? "true" : "false")};
  return std::nullopt;
}

void save_gateway_models(const GatewayModels& m, const std::string& path)
{
  YAML::Emitter e;
  e.SetDoublePrecision(9);
  e << YAML::BeginMap;
  e << YAML::Key << "format" << YAML::Value << kFormat;
  e << YAML::Key << "description" << YAML::Value << m.description;
  e << YAML::Key << "hallway_width_m" << YAML::Value << m.hallway_width;
  e << YAML::Key << "f_vlm" << YAML::Value << m.f_vlm;
  e << YAML::Key << "f_gw" << YAML::Value << m.f_gw;
  e << YAML::Key << "exclude_occluded" << YAML::Value << m.exclude_occluded;
  e << YAML::Key << "over_line_setback_m" << YAML::Value << m.over_line_setback;
  e << YAML::Key << "features" << YAML::Value << hmm_features_name(m.classifier.features());
  e << YAML::Key << "dimension" << YAML::Value << feature_dimension(m.classifier.features());
  int classes = 0;
  for (const auto& h : m.classifier.models()) classes += h ? 1 : 0;
  e << YAML::Key << "classes" << YAML::Value << classes;   // checked on load: a cut-off file has fewer
  e << YAML::Key << "models" << YAML::Value << YAML::BeginMap;
  for (int c = 0; c < kNumSequenceClasses; ++c) {
    const auto& h = m.classifier.models()[static_cast<size_t>(c)];
    if (!h) continue;
    e << YAML::Key << crossing_class_name(c) << YAML::Value << YAML::BeginMap;
    e << YAML::Key << "prior" << YAML::Value;
    emit_numbers(e, h->prior().data(), static_cast<size_t>(h->prior().size()));
    const Eigen::MatrixXd t = h->transition().transpose();  // row-major out
    e << YAML::Key << "transition" << YAML::Value;
    emit_numbers(e, t.data(), static_cast<size_t>(t.size()));
    e << YAML::Key << "states" << YAML::Value << YAML::BeginSeq;
    for (const auto& s : h->state_models()) {
      e << YAML::BeginMap << YAML::Key << "distance_m" << YAML::Value << s.distance;
      e << YAML::Key << "weights" << YAML::Value;
      emit_numbers(e, s.weights.data(), s.weights.size());
      e << YAML::Key << "components" << YAML::Value << YAML::BeginSeq;
      for (const auto& g : s.components) {
        e << YAML::BeginMap << YAML::Key << "mean" << YAML::Value;
        emit_numbers(e, g.mean().data(), static_cast<size_t>(g.mean().size()));
        const Eigen::MatrixXd cov = g.covariance().transpose();
        e << YAML::Key << "covariance" << YAML::Value;
        emit_numbers(e, cov.data(), static_cast<size_t>(cov.size()));
        e << YAML::EndMap;
      }
      e << YAML::EndSeq << YAML::EndMap;
    }
    e << YAML::EndSeq << YAML::EndMap;
  }
  e << YAML::EndMap << YAML::EndMap;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    if (!f) throw std::runtime_error("cannot write " + tmp);
    f << "# Gateway HMMs (diss. 4.1.3.3), written by gateway_trainer; do not edit by hand.\n" << e.c_str() << "\n";
    if (!f) throw std::runtime_error("write failed: " + tmp);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error("cannot rename " + tmp + " to " + path);
}

}  // namespace rgnav::gateway_detector
