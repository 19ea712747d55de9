#include <gtest/gtest.h>

#include <random>

#include "gateway_detector/classifiers.h"
#include "gateway_detector/hmm.h"

namespace rgnav::gateway_detector {
namespace {

// A robot approaching a gateway: the observation drifts as the distance falls from 7 m to 1 m.
// `kind` 0 drifts along x, 1 along y, 2 along x twice as fast and then along y.
TrainingSequence make_sequence(int kind, std::mt19937& rng)
{
  std::normal_distribution<double> noise(0.0, 0.15);
  std::uniform_int_distribution<int> len(8, 20);
  const int n = len(rng);
  TrainingSequence s;
  for (int t = 0; t < n; ++t) {
    const double u = static_cast<double>(t) / (n - 1);  // 0 far .. 1 near
    double x = 0, y = 0;
    if (kind == 0) x = 2 * u;
    if (kind == 1) y = 2 * u;
    if (kind == 2) {
      x = std::min(2.0, 4 * u);
      y = u < 0.5 ? 0.0 : 1.5 * (u - 0.5);
    }
    TrainingObservation o;
    o.features = Eigen::Vector2d(x + noise(rng), y + noise(rng));
    o.distance = 7.0 - 6.0 * u;
    s.push_back(o);
  }
  return s;
}

Sequence features_of(const TrainingSequence& s)
{
  Sequence v;
  for (const auto& o : s) v.push_back(o.features);
  return v;
}

// Training for the synthetic sequences: six states, clusters of at least five observations.
HmmTrainingOptions six_state_training()
{
  HmmTrainingOptions o;
  o.clusters = 6;
  o.min_cluster_size = 5;
  o.state_distance_gap = 1.0;
  o.noise_sigma = 0.05;
  return o;
}

TEST(Gaussian, LogPdfOfAStandardNormal)
{
  const Gaussian g(Eigen::Vector2d::Zero(), Eigen::Matrix2d::Identity());
  EXPECT_NEAR(g.log_pdf(Eigen::Vector2d::Zero()), -std::log(2 * M_PI), 1e-12);
  EXPECT_NEAR(g.log_pdf(Eigen::Vector2d(1, 0)), -std::log(2 * M_PI) - 0.5, 1e-12);
  EXPECT_THROW(Gaussian(Eigen::Vector2d::Zero(), -Eigen::Matrix2d::Identity()), std::invalid_argument);
}

TEST(Hmm, ForwardMatchesBruteForceOnATinyModel)
{
  // Two states, one component each, two observations: sum over the four state paths.
  std::vector<HmmState> st(2);
  st[0].components.emplace_back(Eigen::VectorXd::Constant(1, 0.0), Eigen::MatrixXd::Identity(1, 1));
  st[0].weights = {1.0};
  st[1].components.emplace_back(Eigen::VectorXd::Constant(1, 2.0), Eigen::MatrixXd::Identity(1, 1));
  st[1].weights = {1.0};
  Eigen::Vector2d prior(0.7, 0.3);
  Eigen::Matrix2d a;
  a << 0.6, 0.4, 0.1, 0.9;
  const Hmm h(st, prior, a);
  const Sequence seq = {Eigen::VectorXd::Constant(1, 0.5), Eigen::VectorXd::Constant(1, 1.8)};
  double p = 0;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      p += prior[i] * std::exp(st[i].components[0].log_pdf(seq[0])) * a(i, j) * std::exp(st[j].components[0].log_pdf(seq[1]));
  EXPECT_NEAR(h.log_likelihood(seq), std::log(p), 1e-10);
}

TEST(Hmm, BaumWelchIncreasesTheLikelihoodAndLearnsLeftRight)
{
  std::mt19937 rng(3);
  std::vector<TrainingSequence> train;
  for (int i = 0; i < 60; ++i) train.push_back(make_sequence(0, rng));
  const HmmTrainingOptions o = six_state_training();
  std::vector<double> history;
  const Hmm h = train_hmm(train, o, &history);
  ASSERT_GE(history.size(), 3u);
  for (size_t i = 1; i < history.size(); ++i) EXPECT_GE(history[i], history[i - 1] - 1e-6 * std::fabs(history[i - 1]));
  EXPECT_GT(history.back(), history.front());
  ASSERT_GE(h.states(), 2);
  // States are ordered far -> near; EM from a full 1/Q matrix should leave (almost) nothing
  // below the diagonal, and the prior should favour the far state.
  double backward = 0;
  for (int i = 0; i < h.states(); ++i)
    for (int j = 0; j < i; ++j) backward = std::max(backward, h.transition()(i, j));
  EXPECT_LT(backward, 0.05);
  EXPECT_GT(h.prior()[0], 0.5);
  for (int i = 0; i + 1 < h.states(); ++i) EXPECT_GT(h.state_models()[static_cast<size_t>(i)].distance, h.state_models()[static_cast<size_t>(i + 1)].distance);
}

TEST(Hmm, LeftRightModelsClassifyHeldOutSequences)
{
  std::mt19937 rng(5);
  const HmmTrainingOptions o = six_state_training();
  std::vector<Hmm> models;
  for (int k = 0; k < 3; ++k) {
    std::vector<TrainingSequence> train;
    for (int i = 0; i < 80; ++i) train.push_back(make_sequence(k, rng));
    models.push_back(train_hmm(train, o));
  }
  int correct = 0, total = 0;
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 50; ++i) {
      const Sequence s = features_of(make_sequence(k, rng));
      int best = 0;
      for (int m = 1; m < 3; ++m)
        if (models[static_cast<size_t>(m)].log_likelihood(s) > models[static_cast<size_t>(best)].log_likelihood(s)) best = m;
      correct += best == k;
      ++total;
    }
  EXPECT_GE(correct, total * 97 / 100) << correct << "/" << total;
}

TEST(Hmm, KMeansSeparatesTwoBlobs)
{
  std::vector<Eigen::VectorXd> data;
  for (int i = 0; i < 20; ++i) data.push_back(Eigen::Vector2d(i % 2 ? 0.1 : -0.1, 0));
  for (int i = 0; i < 20; ++i) data.push_back(Eigen::Vector2d(5 + (i % 2 ? 0.1 : -0.1), 5));
  const auto r = kmeans(data, {Eigen::Vector2d(1, 1), Eigen::Vector2d(2, 2)}, 20);
  EXPECT_NEAR(r.centers[0].norm(), 0.0, 1e-9);
  EXPECT_NEAR((r.centers[1] - Eigen::Vector2d(5, 5)).norm(), 0.0, 1e-9);
}

TEST(Classifiers, SocAscAndFusion)
{
  ObservationSequence s(3);
  s[0].weights = {0.1, 0.9, 0, 0, 0, 0, 0, 2.0};  // hallway largest but ignored -> T
  s[0].distance = 6;
  s[1].weights = {0.8, 0.2, 0, 0, 0, 0, 0, 0};
  s[1].distance = 3;
  s[2].weights = {0.1, 0.3, 0, 0, 0, 0, 0.9, 0};
  s[2].distance = 1;
  EXPECT_EQ(soc_last(s), kDeadEnd);
  EXPECT_EQ(soc_last_but_one(s), kX);
  // ASC weights 1/6, 1/3, 1: X = 0.1/6+0.8/3+0.1 = 0.383, dead end = 0.9, T = 0.15+0.067+0.3 = 0.517.
  EXPECT_EQ(asc(s), kDeadEnd);
  ClassLogLikelihoods a{}, b{};
  a.fill(std::log(0.1));
  b.fill(std::log(0.1));
  a[kT] = std::log(0.4);
  b[kT] = std::log(0.2);
  b[kX] = std::log(0.4);
  const auto p = fuse({a, b});
  // T: 0.4 * 0.2 = 0.08, X: 0.1 * 0.4 = 0.04, others 0.01 each (5 of them).
  EXPECT_NEAR(p[kT], 0.08 / 0.17, 1e-9);
  EXPECT_NEAR(p[kX], 0.04 / 0.17, 1e-9);
  const auto q = fuse({a}, {0.0, 1.0, 0, 0, 0, 0, 0});
  EXPECT_NEAR(q[kT], 1.0, 1e-12);
}

TEST(Classifiers, FeatureVectorsOfWeightsAndOfMeasures)
{
  Observation o;
  o.measures.on_line = {0.9, 0.1, 0.2};
  o.measures.over_line = {0.05, 0.8, 0.7};
  o.measures.occluded = {0.0, 0.1, 0.3};
  o.measures.w_d = 0.95;
  o.measures.w_r = 0.97;
  const MeasureOptions mo;
  o.weights = class_weights(o.measures, mo);
  const auto w = feature_vector(o, HmmFeatures::kWeights);
  ASSERT_EQ(w.size(), feature_dimension(HmmFeatures::kWeights));
  for (int c = 0; c < kNumCrossingClasses; ++c) EXPECT_DOUBLE_EQ(w[c], o.weights[static_cast<size_t>(c)]);
  const auto m = feature_vector(o, HmmFeatures::kMeasures);
  ASSERT_EQ(m.size(), feature_dimension(HmmFeatures::kMeasures));
  EXPECT_DOUBLE_EQ(m[0], 0.9);   // left on
  EXPECT_DOUBLE_EQ(m[4], 0.8);   // front over
  EXPECT_DOUBLE_EQ(m[8], 0.3);   // right occluded
  EXPECT_DOUBLE_EQ(m[9], 0.95);  // W_d
  EXPECT_DOUBLE_EQ(m[10], 0.97); // W_r
  // The weights keep only 4 independent numbers: every weight is the dead-end weight plus the
  // (over - on) of the sectors the class leaves open.
  for (int c = 0; c < kNumCrossingClasses; ++c) {
    double v = o.weights[kDeadEnd];
    for (int s = 0; s < 3; ++s)
      if (expects_open(c, s)) v += mo.f_gw / 3 * (o.measures.over_line[static_cast<size_t>(s)] - o.measures.on_line[static_cast<size_t>(s)]);
    EXPECT_NEAR(o.weights[static_cast<size_t>(c)], v, 1e-12) << crossing_class_name(c);
  }
  EXPECT_EQ(hmm_features_from_name(hmm_features_name(HmmFeatures::kMeasures)), HmmFeatures::kMeasures);
  EXPECT_EQ(hmm_features_from_name(hmm_features_name(HmmFeatures::kWeights)), HmmFeatures::kWeights);
  EXPECT_FALSE(hmm_features_from_name("pixels").has_value());
}

}  // namespace
}  // namespace rgnav::gateway_detector
