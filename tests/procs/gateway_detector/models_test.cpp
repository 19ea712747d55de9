#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "bad_files.h"
#include "config/config.h"
#include "gateway_detector/gateway_models.h"
#include "gateway_detector/options.h"

namespace rgnav::gateway_detector {
namespace {

// Trains c's model of each of `classes` on `sequences` synthetic sequences of `length`
// observations each, observation(cls, t) making the t-th (called in that order).
template <class MakeObservation>
void train_classes(HmmClassifier* c, std::initializer_list<int> classes, int sequences, int length, int clusters,
                   MakeObservation observation)
{
  for (int cls : classes) {
    std::vector<TrainingSequence> seqs;
    for (int s = 0; s < sequences; ++s) {
      TrainingSequence seq;
      for (int t = 0; t < length; ++t) seq.push_back(observation(cls, t));
      seqs.push_back(seq);
    }
    HmmTrainingOptions o;
    o.clusters = clusters;
    o.min_cluster_size = 5;
    c->models()[static_cast<size_t>(cls)] = train_hmm(seqs, o);
  }
}

HmmClassifier small_classifier()
{
  std::mt19937 rng(1);
  std::normal_distribution<double> n(0, 0.05);
  HmmClassifier c;
  train_classes(&c, {int{kT}, int{kX}}, 20, 10, 3, [&](int cls, int t) {
    TrainingObservation o;
    o.features = Eigen::VectorXd::Zero(kNumCrossingClasses);
    for (int k = 0; k < kNumCrossingClasses; ++k) o.features[k] = 0.5 + n(rng);
    o.features[cls] += 0.05 * t;
    o.distance = 7.0 - 0.6 * t;
    return o;
  });
  return c;
}

// Models for a 2 m hallway around small_classifier().
GatewayModels small_models()
{
  GatewayModels m;
  m.hallway_width = 2.0;
  m.f_vlm = 0.5;
  m.f_gw = 1.0;
  m.classifier = small_classifier();
  return m;
}

std::string temp_path(const std::string& name)
{
  return (std::filesystem::temp_directory_path() / ("gw_models_" + std::to_string(::getpid()) + "_" + name)).string();
}

TEST(GatewayModels, SaveLoadRoundTrip)
{
  GatewayModels m = small_models();
  m.description = "unit test";
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
  const GatewayModels m = small_models();
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

// Issue 35: a model file of random bytes, an empty one and one cut off mid-content (inside a
// list of numbers, and at a line boundary) are refused naming the file.
TEST(GatewayModels, RandomBytesEmptyAndCutOffFilesAreRefusedNamingThem)
{
  const GatewayModels m = small_models();
  testing::TempDir dir("models_bad");
  save_gateway_models(m, dir.file("valid.yaml"));
  const std::string text = testing::read_file(dir.file("valid.yaml"));
  ASSERT_NO_THROW(load_gateway_models(dir.file("valid.yaml")));
  auto files = testing::write_bad_files(dir.path(), "models.yaml", text, text.find("[", text.size() / 2) + 4);
  files.push_back({"cut at a line end", dir.file("line_cut.yaml")});
  testing::write_bytes(files.back().path, text.substr(0, text.find("\n", text.size() / 2) + 1));
  for (const auto& f : files) {
    SCOPED_TRACE(f.kind);
    try {
      load_gateway_models(f.path);
      ADD_FAILURE() << f.path << " was loaded";
    } catch (const config::ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(f.path + ": ", 0), 0u) << e.what();
    }
  }
}

TEST(GatewayModels, MeasureFeaturesRoundTripAndMismatchesAreNamed)
{
  std::mt19937 rng(2);
  std::normal_distribution<double> n(0, 0.03);
  HmmClassifier c(HmmFeatures::kMeasures);
  train_classes(&c, {int{kLTurn}, int{kDeadEnd}}, 15, 8, 2, [&](int cls, int t) {
    Observation ob;
    ob.measures.on_line = {cls == kLTurn ? 0.1 + n(rng) : 0.9 + n(rng), 0.9 + n(rng), 0.9 + n(rng)};
    ob.measures.over_line = {cls == kLTurn ? 0.8 + n(rng) : 0.05 + n(rng), 0.05 + n(rng), 0.05 + n(rng)};
    ob.measures.occluded = {0.02 + n(rng), 0.02 + n(rng), 0.02 + n(rng)};
    ob.measures.w_d = 0.9 + n(rng);
    ob.measures.w_r = 0.95 + n(rng);
    return TrainingObservation{feature_vector(ob, HmmFeatures::kMeasures), 6.0 - 0.6 * t};
  });
  GatewayModels m;
  m.hallway_width = 2.5;
  m.f_vlm = 0.5;
  m.f_gw = 1.0;
  m.exclude_occluded = true;
  m.over_line_setback = 0.75;
  m.classifier = c;
  const auto path = temp_path("measures.yaml");
  save_gateway_models(m, path);
  const auto back = load_gateway_models(path);
  EXPECT_EQ(back.classifier.features(), HmmFeatures::kMeasures);
  EXPECT_TRUE(back.exclude_occluded);
  ObservationSequence turn(4);
  for (auto& ob : turn) {
    ob.measures.on_line = {0.1, 0.9, 0.9};
    ob.measures.over_line = {0.8, 0.05, 0.05};
    ob.measures.occluded = {0.02, 0.02, 0.02};
    ob.measures.w_d = 0.9;
    ob.measures.w_r = 0.95;
  }
  EXPECT_EQ(back.classifier.classify(turn), kLTurn);
  // The detector refuses features made differently from the training.
  MeasureOptions mo;
  mo.hallway_width = 2.5;
  mo.exclude_occluded = true;
  EXPECT_EQ(models_mismatch(back, mo)->key, "over_line_setback_m");
  mo.over_line_setback = 0.75;
  EXPECT_FALSE(models_mismatch(back, mo).has_value());
  mo.exclude_occluded = false;
  ASSERT_TRUE(models_mismatch(back, mo).has_value());
  EXPECT_EQ(models_mismatch(back, mo)->key, "exclude_occluded");
  mo.exclude_occluded = true;
  mo.hallway_width = 2.0;
  EXPECT_EQ(models_mismatch(back, mo)->key, "hallway_width_m");
  // A file whose feature set and dimension disagree is refused.
  std::string text;
  {
    std::ifstream f(path);
    text.assign(std::istreambuf_iterator<char>(f), {});
  }
  text.replace(text.find("features: measures"), 18, "features: weights ");
  {
    std::ofstream f(path);
    f << text;
  }
  EXPECT_THROW(load_gateway_models(path), config::ConfigError);
  std::filesystem::remove(path);
}

TEST(GatewayModels, CheckedInModelsLoad)
{
  const std::string path = RGNAV_SOURCE_DIR "/config/gateway_models/default.yaml";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no trained models (./rgnav train-gateways)";
  const auto m = load_gateway_models(path);
  EXPECT_GT(m.hallway_width, 0.0);
  for (int c = 0; c < kNumSequenceClasses; ++c) EXPECT_TRUE(m.classifier.models()[static_cast<size_t>(c)].has_value()) << c;
  // They were trained on features made the way every shipped detector config makes them (the
  // demo's aligned config once kept an old setback, and its detector refused to start).
  for (const char* name : {"gateway_detector.yaml", "gateway_detector_aligned.yaml"}) {
    const auto o = load_detector_options(config::Config::load(std::string(RGNAV_SOURCE_DIR "/config/") + name),
                                         config::load_robot_description_file(RGNAV_SOURCE_DIR "/config/robot.yaml"));
    const auto bad = models_mismatch(m, o.measures);
    EXPECT_FALSE(bad.has_value()) << name << ": " << bad->key << ": " << bad->reason;
  }
}

}  // namespace
}  // namespace rgnav::gateway_detector
