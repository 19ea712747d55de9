// Classifiers of crossing observation sequences (diss. 4.1.3): the single observation
// classifier on the last or the last but one observation (SOC), the averaged sequence
// classifier with weights inversely proportional to distance (ASC), and the per-class HMMs
// with Bayes fusion of sequence likelihoods. SOC and ASC ignore the hallway weight, as in the
// dissertation (it is large wherever there is open space ahead).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "gateway_detector/hmm.h"
#include "gateway_detector/measures.h"

namespace rgnav::gateway_detector {

struct Observation
{
  ObservationVector weights{};
  Measures measures;      // what the weights were made of
  double distance = 0.0;  // [m] robot to crossing point
};
using ObservationSequence = std::vector<Observation>;

// Index of the largest weight among the sequence classes (hallway ignored); -1 if empty.
int soc(const ObservationVector& w);
int soc_last(const ObservationSequence& s);
int soc_last_but_one(const ObservationSequence& s);  // falls back to the last for length 1
int asc(const ObservationSequence& s, double min_distance = 0.5);

using ClassLogLikelihoods = std::array<double, kNumSequenceClasses>;
using ClassProbabilities = std::array<double, kNumSequenceClasses>;

// What the HMMs observe. kWeights: the dissertation's observation vector W(GW, VLM). Every
// weight is the same general term plus, per sector, either its On Line or its Over Line FSM,
// so the eight weights span only a 4-dimensional affine subspace: they keep on - over per
// sector but lose whether a sector is a wall (on high), an opening (over high) or hidden by
// clutter (both low). kMeasures: the measures themselves, per sector On Line, Over Line and
// the occluded fraction, then W_d and W_r (11 numbers).
enum class HmmFeatures { kWeights, kMeasures };
int feature_dimension(HmmFeatures f);
const char* hmm_features_name(HmmFeatures f);
std::optional<HmmFeatures> hmm_features_from_name(const std::string& name);
Eigen::VectorXd feature_vector(const Observation& o, HmmFeatures f = HmmFeatures::kWeights);

// One HMM per sequence class; a class without a model never wins.
class HmmClassifier
{
 public:
  HmmClassifier() = default;
  explicit HmmClassifier(HmmFeatures features) : features_(features) {}
  HmmFeatures features() const { return features_; }
  std::array<std::optional<Hmm>, kNumSequenceClasses>& models() { return models_; }
  const std::array<std::optional<Hmm>, kNumSequenceClasses>& models() const { return models_; }
  bool empty() const;
  ClassLogLikelihoods log_likelihoods(const ObservationSequence& s) const;
  int classify(const ObservationSequence& s) const;

 private:
  HmmFeatures features_ = HmmFeatures::kWeights;
  std::array<std::optional<Hmm>, kNumSequenceClasses> models_;
};

// Bayes fusion: posterior(c) ∝ prior(c) * prod_k P(sequence_k | c); uniform prior if empty.
ClassProbabilities fuse(const std::vector<ClassLogLikelihoods>& sequences, const std::vector<double>& prior = {});
// Normalised weights as pseudo-probabilities (what is published when no HMMs are loaded).
ClassProbabilities weights_to_probabilities(const ObservationVector& w);

}  // namespace rgnav::gateway_detector
