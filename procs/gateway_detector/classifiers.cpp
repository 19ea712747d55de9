#include "gateway_detector/classifiers.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::gateway_detector {

int soc(const ObservationVector& w)
{
  int best = 0;
  for (int c = 1; c < kNumSequenceClasses; ++c)
    if (w[c] > w[best]) best = c;
  return best;
}

int soc_last(const ObservationSequence& s) { return s.empty() ? -1 : soc(s.back().weights); }

int soc_last_but_one(const ObservationSequence& s)
{
  if (s.empty()) return -1;
  return soc(s[s.size() >= 2 ? s.size() - 2 : 0].weights);
}

int asc(const ObservationSequence& s, double min_distance)
{
  if (s.empty()) return -1;
  ObservationVector avg{};
  double total = 0.0;
  for (const auto& o : s) {
    const double w = 1.0 / std::max(min_distance, o.distance);
    for (int c = 0; c < kNumCrossingClasses; ++c) avg[c] += w * o.weights[c];
    total += w;
  }
  for (auto& a : avg) a /= total;
  return soc(avg);
}

int feature_dimension(HmmFeatures f) { return f == HmmFeatures::kWeights ? kNumCrossingClasses : 11; }

const char* hmm_features_name(HmmFeatures f) { return f == HmmFeatures::kWeights ? "weights" : "measures"; }

std::optional<HmmFeatures> hmm_features_from_name(const std::string& name)
{
  if (name == "weights") return HmmFeatures::kWeights;
  if (name == "measures") return HmmFeatures::kMeasures;
  return std::nullopt;
}

Eigen::VectorXd feature_vector(const Observation& o, HmmFeatures f)
{
  Eigen::VectorXd v(feature_dimension(f));
  if (f == HmmFeatures::kWeights) {
    for (int c = 0; c < kNumCrossingClasses; ++c) v[c] = o.weights[c];
    return v;
  }
  const auto& m = o.measures;
  for (int s = 0; s < 3; ++s) {
    v[3 * s] = m.on_line[static_cast<size_t>(s)];
    v[3 * s + 1] = m.over_line[static_cast<size_t>(s)];
    v[3 * s + 2] = m.occluded[static_cast<size_t>(s)];
  }
  v[9] = m.w_d;
  v[10] = m.w_r;
  return v;
}

bool HmmClassifier::empty() const
{
  return std::none_of(models_.begin(), models_.end(), [](const auto& m) { return m.has_value(); });
}

ClassLogLikelihoods HmmClassifier::log_likelihoods(const ObservationSequence& s) const
{
  Sequence seq;
  for (const auto& o : s) seq.push_back(feature_vector(o, features_));
  ClassLogLikelihoods ll;
  for (int c = 0; c < kNumSequenceClasses; ++c)
    ll[c] = models_[c] ? models_[c]->log_likelihood(seq) : -std::numeric_limits<double>::infinity();
  return ll;
}

int HmmClassifier::classify(const ObservationSequence& s) const
{
  if (s.empty() || empty()) return -1;
  const auto ll = log_likelihoods(s);
  return static_cast<int>(std::max_element(ll.begin(), ll.end()) - ll.begin());
}

ClassProbabilities fuse(const std::vector<ClassLogLikelihoods>& sequences, const std::vector<double>& prior)
{
  std::array<double, kNumSequenceClasses> lp;
  for (int c = 0; c < kNumSequenceClasses; ++c) {
    lp[c] = prior.empty() ? 0.0 : (prior[c] > 0 ? std::log(prior[c]) : -std::numeric_limits<double>::infinity());
    for (const auto& s : sequences) lp[c] += s[c];
  }
  const double m = *std::max_element(lp.begin(), lp.end());
  ClassProbabilities p{};
  if (!std::isfinite(m)) {
    p.fill(1.0 / kNumSequenceClasses);
    return p;
  }
  double sum = 0.0;
  for (int c = 0; c < kNumSequenceClasses; ++c) sum += (p[c] = std::exp(lp[c] - m));
  for (auto& x : p) x /= sum;
  return p;
}

ClassProbabilities weights_to_probabilities(const ObservationVector& w)
{
  ClassProbabilities p{};
  double sum = 0.0;
  for (int c = 0; c < kNumSequenceClasses; ++c) sum += (p[c] = std::max(0.0, w[c]));
  for (auto& x : p) x = sum > 0 ? x / sum : 1.0 / kNumSequenceClasses;
  return p;
}

}  // namespace rgnav::gateway_detector
