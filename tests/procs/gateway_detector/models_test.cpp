#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "config/config.h"
#include "gateway_detector/gateway_models.h"

namespace rgnav::gateway_detector {
namespace {

HmmClassifier small_classifier()
{
  std::mt19937 rng(1);
  std::normal_distribution<double> n(0, 0.05);
  HmmClassifier c;
  for (int cls : {int{kT}, int{kX}}) {
    std::vector<TrainingSequence> seqs;
    for (int s = 0; s < 20; ++s) {
      TrainingSequence seq;
      for (int t = 0; t < 10; ++t) {
        TrainingObservation o;
        o.features = Eigen::VectorXd::Zero(kNumCrossingClasses);
        for (int k = 0; k < kNumCrossingClasses; ++k) o.features[k] = 0.5 + n(rng);
        o.features[cls] += 0.05 * t;
        o.distance = 7.0 - 0.6 * t;
        seq.push_back(o);
      }
      seqs.push_back(seq);
    }
    HmmTrainingOptions o;
    o.clusters = 3;
    o.min_cluster_size = 5;
    c.models()[static_cast<size_t>(cls)] = train_hmm(seqs, o);
  }
  return c;
}

std::string temp_path(const std::string& name)
{
  return (std::filesystem::temp_directory_path() / ("gw_models_" + std::to_string(::getpid()) + "_" + name)).string();
}

TEST(GatewayModels, SaveLoadRoundTrip)
{
  GatewayModels m;
  m.description = "unit test";
  m.hallway_width = 2.0;
  m.f_vlm = 0.5;
  m.f_gw = 1.0;
  m.classifier = small_classifier();
  const auto path = temp_path("ok.yaml");
  save_gateway_models(m, path);
  const auto back = load_gateway_models(path);
  EXPECT_EQ(back.description, "unit test");
  ObservationSequence s(5);
  for (auto& o : s) o.weights.fill(0.6);
  const auto a = m.classifier.log_likelihoods(s), b = back.classifier.log_likelihoods(s);
  for (int c = 0; c < kNumSequenceClasses; ++c) {
    if (std::isfinite(a[c])) EXPECT_NEAR(a[c], b[c], 1e-5 * std::fabs(a[c]) + 1e-6);
    else EXPECT_FALSE(std::isfinite(b[c]));
  }
  std::filesystem::remove(path);
}

TEST(GatewayModels, BrokenFilesAreRefusedWithTheKey)
{
  GatewayModels m;
  m.hallway_width = 2.0;
  m.f_vlm = 0.5;
  m.f_gw = 1.0;
  m.classifier = small_classifier();
  const auto path = temp_path("bad.yaml");
  save_gateway_models(m, path);
  std::string text;
  {
    std::ifstream f(path);
    text.assign(std::istreambuf_iterator<char>(f), {});
  }
  auto expect_refused = [&](const std::string& bad, const std::string& key) {
    {
      std::ofstream f(path);
      f << bad;
    }
    try {
      load_gateway_models(path);
      ADD_FAILURE() << "accepted: " << key;
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  expect_refused(text + "typo_key: 1\n", "typo_key");
  std::string unknown_class = text;
  unknown_class.replace(unknown_class.find("t_crossing:"), 11, "q_crossing:");
  expect_refused(unknown_class, "q_crossing");
  std::string no_format = text;
  no_format.replace(no_format.find("rgnav-gateway-hmm-1"), 19, "something-else-1234");
  expect_refused(no_format, "format");
  // A negative variance: not positive definite.
  std::string bad_cov = text;
  const auto at = bad_cov.find("covariance: [");
  ASSERT_NE(at, std::string::npos);
  bad_cov.insert(at + 13, "-");
  expect_refused(bad_cov, "covariance");
  std::filesystem::remove(path);
}

TEST(GatewayModels, CheckedInModelsLoad)
{
  const std::string path = RGNAV_SOURCE_DIR "/config/gateway_models/default.yaml";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no trained models (./rgnav train-gateways)";
  const auto m = load_gateway_models(path);
  EXPECT_GT(m.hallway_width, 0.0);
  for (int c = 0; c < kNumSequenceClasses; ++c) EXPECT_TRUE(m.classifier.models()[static_cast<size_t>(c)].has_value()) << c;
}

}  // namespace
}  // namespace rgnav::gateway_detector
