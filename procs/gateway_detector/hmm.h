// Continuous-output HMMs for gateway observation sequences (diss. 4.1.3.3, after Rabiner):
// observation models are Gaussian mixtures built from k-means clusters of the training
// vectors, clusters of about the same distance to the gateway form one state, states are
// ordered far -> near (left-right), and EM (Baum-Welch) learns the prior, the transition
// matrix (initialised full, 1/Q, so that the left-right structure has to emerge) and the
// mixture weights with the observation densities held fixed. Noise against over-fitting is
// added as its expectation: sigma^2 I on every cluster covariance.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <vector>

namespace rgnav::gateway_detector {

class Gaussian
{
 public:
  Gaussian() = default;
  // Throws std::invalid_argument unless cov is symmetric positive definite of mean's size.
  Gaussian(Eigen::VectorXd mean, Eigen::MatrixXd cov);
  double log_pdf(const Eigen::VectorXd& x) const;
  const Eigen::VectorXd& mean() const { return mean_; }
  const Eigen::MatrixXd& covariance() const { return cov_; }

 private:
  Eigen::VectorXd mean_;
  Eigen::MatrixXd cov_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  double log_norm_ = 0.0;
};

struct HmmState
{
  double distance = 0.0;                // [m] mean distance to the gateway of its clusters
  std::vector<Gaussian> components;
  std::vector<double> weights;          // mixture weights (a row of M_mix), sum to 1
};

using Sequence = std::vector<Eigen::VectorXd>;

class Hmm
{
 public:
  Hmm() = default;
  // Throws std::invalid_argument on inconsistent sizes or non-stochastic rows.
  Hmm(std::vector<HmmState> states, Eigen::VectorXd prior, Eigen::MatrixXd transition);

  // log P(sequence | model) by the scaled forward algorithm; -inf if impossible.
  double log_likelihood(const Sequence& seq) const;
  // Baum-Welch over prior, transition and mixture weights. Returns the total log-likelihood
  // of the training set before each iteration and after the last one.
  std::vector<double> baum_welch(const std::vector<Sequence>& sequences, int iterations, double tolerance);
  // Keeps every transition and prior entry >= floor (renormalised) so that an unusual order
  // of observations lowers the likelihood instead of making it zero.
  void floor_probabilities(double floor);

  int states() const { return static_cast<int>(states_.size()); }
  int dimension() const { return states_.empty() ? 0 : static_cast<int>(states_[0].components[0].mean().size()); }
  const std::vector<HmmState>& state_models() const { return states_; }
  const Eigen::VectorXd& prior() const { return prior_; }
  const Eigen::MatrixXd& transition() const { return transition_; }

 private:
  // log b_q(o) per state and per component.
  void emission(const Eigen::VectorXd& o, Eigen::VectorXd* log_b, std::vector<Eigen::VectorXd>* log_comp) const;

  std::vector<HmmState> states_;
  Eigen::VectorXd prior_;
  Eigen::MatrixXd transition_;
};

struct HmmTrainingOptions
{
  int clusters = 8;                 // k of k-means
  double window_overlap = 0.5;      // overlap of the distance-sorted windows that seed k-means
  int kmeans_iterations = 50;
  int min_cluster_size = 10;        // smaller clusters are dropped
  double state_distance_gap = 0.6;  // [m] clusters whose mean distances differ less share a state
  double noise_sigma = 0.03;        // std of the noise spread over the clusters (sigma^2 I)
  int em_iterations = 40;
  double em_tolerance = 1e-4;       // relative change of the log-likelihood that ends EM
  double probability_floor = 1e-4;  // after EM
};

struct TrainingObservation
{
  Eigen::VectorXd features;
  double distance = 0.0;  // [m] to the gateway when observed
};
using TrainingSequence = std::vector<TrainingObservation>;

struct KMeansResult
{
  std::vector<Eigen::VectorXd> centers;
  std::vector<int> assignment;
};
// Lloyd's algorithm from the given start centres.
KMeansResult kmeans(const std::vector<Eigen::VectorXd>& data, std::vector<Eigen::VectorXd> centers, int iterations);

// Clusters, initialises and trains one class's HMM; throws std::invalid_argument without data.
Hmm train_hmm(const std::vector<TrainingSequence>& sequences, const HmmTrainingOptions& options,
              std::vector<double>* em_log_likelihoods = nullptr);

}  // namespace rgnav::gateway_detector
