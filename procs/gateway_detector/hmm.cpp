#include "gateway_detector/hmm.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace rgnav::gateway_detector {

namespace {
constexpr double kNegInf = -std::numeric_limits<double>::infinity();

double log_sum_exp(const Eigen::VectorXd& v)
{
  const double m = v.maxCoeff();
  if (!std::isfinite(m)) return m;
  return m + std::log((v.array() - m).exp().sum());
}
}  // namespace

Gaussian::Gaussian(Eigen::VectorXd mean, Eigen::MatrixXd cov) : mean_(std::move(mean)), cov_(std::move(cov))
{
  const auto d = mean_.size();
  if (d == 0 || cov_.rows() != d || cov_.cols() != d) throw std::invalid_argument("Gaussian: covariance size != mean size");
  if (!cov_.allFinite() || !mean_.allFinite()) throw std::invalid_argument("Gaussian: non-finite parameters");
  if ((cov_ - cov_.transpose()).cwiseAbs().maxCoeff() > 1e-9 * std::max(1.0, cov_.cwiseAbs().maxCoeff()))
    throw std::invalid_argument("Gaussian: covariance not symmetric");
  llt_.compute(cov_);
  if (llt_.info() != Eigen::Success) throw std::invalid_argument("Gaussian: covariance not positive definite");
  const Eigen::MatrixXd l = llt_.matrixL();
  double log_det = 0.0;
  for (Eigen::Index i = 0; i < d; ++i) {
    if (!(l(i, i) > 0)) throw std::invalid_argument("Gaussian: covariance not positive definite");
    log_det += 2.0 * std::log(l(i, i));
  }
  log_norm_ = -0.5 * (static_cast<double>(d) * std::log(2.0 * M_PI) + log_det);
}

double Gaussian::log_pdf(const Eigen::VectorXd& x) const
{
  const Eigen::VectorXd z = llt_.matrixL().solve(x - mean_);
  return log_norm_ - 0.5 * z.squaredNorm();
}

Hmm::Hmm(std::vector<HmmState> states, Eigen::VectorXd prior, Eigen::MatrixXd transition)
    : states_(std::move(states)), prior_(std::move(prior)), transition_(std::move(transition))
{
  const auto q = static_cast<Eigen::Index>(states_.size());
  if (q == 0) throw std::invalid_argument("Hmm: no states");
  if (prior_.size() != q || transition_.rows() != q || transition_.cols() != q)
    throw std::invalid_argument("Hmm: prior/transition size != number of states");
  auto stochastic = [](const Eigen::VectorXd& v) {
    return v.allFinite() && v.minCoeff() >= 0.0 && std::fabs(v.sum() - 1.0) < 1e-6;
  };
  if (!stochastic(prior_)) throw std::invalid_argument("Hmm: prior is not a probability vector");
  for (Eigen::Index i = 0; i < q; ++i)
    if (!stochastic(transition_.row(i).transpose())) throw std::invalid_argument("Hmm: transition row is not stochastic");
  const auto d = states_[0].components.empty() ? 0 : states_[0].components[0].mean().size();
  for (const auto& s : states_) {
    if (s.components.empty() || s.components.size() != s.weights.size())
      throw std::invalid_argument("Hmm: state without components or weights");
    Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(s.weights.data(), static_cast<Eigen::Index>(s.weights.size()));
    if (!stochastic(w)) throw std::invalid_argument("Hmm: mixture weights do not sum to 1");
    for (const auto& c : s.components)
      if (c.mean().size() != d) throw std::invalid_argument("Hmm: components of different dimension");
  }
}

void Hmm::emission(const Eigen::VectorXd& o, Eigen::VectorXd* log_b, std::vector<Eigen::VectorXd>* log_comp) const
{
  const auto q = states_.size();
  log_b->resize(static_cast<Eigen::Index>(q));
  if (log_comp) log_comp->resize(q);
  for (size_t i = 0; i < q; ++i) {
    const auto& s = states_[i];
    Eigen::VectorXd lc(static_cast<Eigen::Index>(s.components.size()));
    for (size_t m = 0; m < s.components.size(); ++m)
      lc[static_cast<Eigen::Index>(m)] = (s.weights[m] > 0 ? std::log(s.weights[m]) : kNegInf) + s.components[m].log_pdf(o);
    (*log_b)[static_cast<Eigen::Index>(i)] = log_sum_exp(lc);
    if (log_comp) (*log_comp)[i] = lc;
  }
}

double Hmm::log_likelihood(const Sequence& seq) const
{
  if (seq.empty()) return 0.0;
  Eigen::VectorXd log_b;
  Eigen::VectorXd alpha;
  double ll = 0.0;
  for (size_t t = 0; t < seq.size(); ++t) {
    emission(seq[t], &log_b, nullptr);
    const double m = log_b.maxCoeff();
    if (!std::isfinite(m)) return kNegInf;
    const Eigen::VectorXd b = (log_b.array() - m).exp();
    alpha = t == 0 ? Eigen::VectorXd(prior_.cwiseProduct(b)) : Eigen::VectorXd((transition_.transpose() * alpha).cwiseProduct(b));
    const double c = alpha.sum();
    if (!(c > 0)) return kNegInf;
    alpha /= c;
    ll += std::log(c) + m;
  }
  return ll;
}

std::vector<double> Hmm::baum_welch(const std::vector<Sequence>& sequences, int iterations, double tolerance)
{
  const auto q = static_cast<Eigen::Index>(states_.size());
  std::vector<double> history;
  for (int it = 0; it <= iterations; ++it) {
    Eigen::VectorXd prior_acc = Eigen::VectorXd::Zero(q);
    Eigen::MatrixXd trans_acc = Eigen::MatrixXd::Zero(q, q);
    std::vector<Eigen::VectorXd> mix_acc(states_.size());
    for (size_t i = 0; i < states_.size(); ++i) mix_acc[i] = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(states_[i].weights.size()));
    double total = 0.0;
    int used = 0;

    for (const auto& seq : sequences) {
      const auto T = seq.size();
      if (T == 0) continue;
      std::vector<Eigen::VectorXd> b(T), alpha(T), beta(T);
      std::vector<std::vector<Eigen::VectorXd>> log_comp(T);
      std::vector<double> scale(T);
      Eigen::VectorXd log_b;
      bool ok = true;
      double ll = 0.0;
      for (size_t t = 0; t < T; ++t) {
        emission(seq[t], &log_b, &log_comp[t]);
        const double m = log_b.maxCoeff();
        if (!std::isfinite(m)) { ok = false; break; }
        b[t] = (log_b.array() - m).exp();
        // Keep log b for the mixture responsibilities (relative to state).
        for (Eigen::Index i = 0; i < q; ++i) log_comp[t][static_cast<size_t>(i)].array() -= log_b[i];
        alpha[t] = t == 0 ? Eigen::VectorXd(prior_.cwiseProduct(b[t])) : Eigen::VectorXd((transition_.transpose() * alpha[t - 1]).cwiseProduct(b[t]));
        scale[t] = alpha[t].sum();
        if (!(scale[t] > 0)) { ok = false; break; }
        alpha[t] /= scale[t];
        ll += std::log(scale[t]) + m;
      }
      if (!ok) continue;  // a sequence this model cannot explain teaches it nothing
      total += ll;
      ++used;
      beta[T - 1] = Eigen::VectorXd::Ones(q);
      for (size_t t = T - 1; t-- > 0;) {
        beta[t] = transition_ * b[t + 1].cwiseProduct(beta[t + 1]);
        beta[t] /= scale[t + 1];
      }
      for (size_t t = 0; t < T; ++t) {
        Eigen::VectorXd gamma = alpha[t].cwiseProduct(beta[t]);
        const double g = gamma.sum();
        if (g > 0) gamma /= g;
        if (t == 0) prior_acc += gamma;
        for (Eigen::Index i = 0; i < q; ++i)
          mix_acc[static_cast<size_t>(i)] += gamma[i] * log_comp[t][static_cast<size_t>(i)].array().exp().matrix();
        if (t + 1 < T) {
          // xi_t(i, j) = alpha_t(i) a_ij b_j(o_t+1) beta_t+1(j) / scale_t+1
          const Eigen::MatrixXd xi = (alpha[t] * (b[t + 1].cwiseProduct(beta[t + 1])).transpose()).cwiseProduct(transition_) / scale[t + 1];
          trans_acc += xi;
        }
      }
    }
    history.push_back(total);
    if (used == 0 || it == iterations) break;
    if (history.size() >= 2) {
      const double prev = history[history.size() - 2];
      if (std::fabs(total - prev) <= tolerance * std::fabs(prev)) break;
    }
    // M step.
    if (prior_acc.sum() > 0) prior_ = prior_acc / prior_acc.sum();
    for (Eigen::Index i = 0; i < q; ++i) {
      const double r = trans_acc.row(i).sum();
      if (r > 0) transition_.row(i) = trans_acc.row(i) / r;
      const double mw = mix_acc[static_cast<size_t>(i)].sum();
      if (mw > 0)
        for (size_t m = 0; m < states_[static_cast<size_t>(i)].weights.size(); ++m)
          states_[static_cast<size_t>(i)].weights[m] = mix_acc[static_cast<size_t>(i)][static_cast<Eigen::Index>(m)] / mw;
    }
  }
  return history;
}

void Hmm::floor_probabilities(double floor)
{
  auto fix = [floor](auto&& v) {
    v = v.cwiseMax(floor);
    v /= v.sum();
  };
  fix(prior_);
  for (Eigen::Index i = 0; i < transition_.rows(); ++i) {
    Eigen::VectorXd r = transition_.row(i).transpose();
    fix(r);
    transition_.row(i) = r.transpose();
  }
  for (auto& s : states_) {
    Eigen::VectorXd w = Eigen::Map<Eigen::VectorXd>(s.weights.data(), static_cast<Eigen::Index>(s.weights.size()));
    fix(w);
    for (size_t m = 0; m < s.weights.size(); ++m) s.weights[m] = w[static_cast<Eigen::Index>(m)];
  }
}

KMeansResult kmeans(const std::vector<Eigen::VectorXd>& data, std::vector<Eigen::VectorXd> centers, int iterations)
{
  KMeansResult r;
  r.assignment.assign(data.size(), -1);
  for (int it = 0; it < iterations; ++it) {
    bool changed = false;
    for (size_t n = 0; n < data.size(); ++n) {
      int best = 0;
      double bd = std::numeric_limits<double>::infinity();
      for (size_t k = 0; k < centers.size(); ++k) {
        const double d = (data[n] - centers[k]).squaredNorm();
        if (d < bd) { bd = d; best = static_cast<int>(k); }
      }
      if (best != r.assignment[n]) { r.assignment[n] = best; changed = true; }
    }
    std::vector<Eigen::VectorXd> sum(centers.size(), Eigen::VectorXd::Zero(centers[0].size()));
    std::vector<int> count(centers.size(), 0);
    for (size_t n = 0; n < data.size(); ++n) {
      sum[static_cast<size_t>(r.assignment[n])] += data[n];
      ++count[static_cast<size_t>(r.assignment[n])];
    }
    for (size_t k = 0; k < centers.size(); ++k)
      if (count[k] > 0) centers[k] = sum[k] / count[k];
    if (!changed) break;
  }
  r.centers = std::move(centers);
  return r;
}

Hmm train_hmm(const std::vector<TrainingSequence>& sequences, const HmmTrainingOptions& o, std::vector<double>* em_ll)
{
  std::vector<TrainingObservation> all;
  for (const auto& s : sequences) all.insert(all.end(), s.begin(), s.end());
  if (all.empty()) throw std::invalid_argument("train_hmm: no training observations");
  const auto dim = all[0].features.size();
  // Far to near, so that windows (and hence the seeds) follow the distance to the gateway.
  std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.distance > b.distance; });
  const int k = std::max(1, std::min(o.clusters, static_cast<int>(all.size())));
  const double n = static_cast<double>(all.size());
  const double window = n / (1.0 + (k - 1) * (1.0 - o.window_overlap));
  const double step = window * (1.0 - o.window_overlap);
  std::vector<Eigen::VectorXd> seeds;
  std::vector<Eigen::VectorXd> data;
  for (const auto& a : all) data.push_back(a.features);
  for (int c = 0; c < k; ++c) {
    const auto lo = static_cast<size_t>(std::floor(c * step));
    const auto hi = std::min(all.size(), std::max(lo + 1, static_cast<size_t>(std::ceil(c * step + window))));
    Eigen::VectorXd m = Eigen::VectorXd::Zero(dim);
    for (size_t i = lo; i < hi; ++i) m += data[i];
    seeds.push_back(m / static_cast<double>(hi - lo));
  }
  const KMeansResult km = kmeans(data, seeds, o.kmeans_iterations);

  struct Cluster
  {
    Eigen::VectorXd mean;
    Eigen::MatrixXd cov;
    double distance;
    int size;
  };
  std::vector<Cluster> clusters;
  const int min_size = std::min(o.min_cluster_size, static_cast<int>(all.size()));
  for (int c = 0; c < k; ++c) {
    Eigen::VectorXd mean = Eigen::VectorXd::Zero(dim);
    double dist = 0.0;
    int cnt = 0;
    for (size_t i = 0; i < all.size(); ++i)
      if (km.assignment[i] == c) { mean += data[i]; dist += all[i].distance; ++cnt; }
    if (cnt < std::max(1, min_size)) continue;
    mean /= cnt;
    Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(dim, dim);
    for (size_t i = 0; i < all.size(); ++i)
      if (km.assignment[i] == c) cov += (data[i] - mean) * (data[i] - mean).transpose();
    cov /= cnt;
    cov += o.noise_sigma * o.noise_sigma * Eigen::MatrixXd::Identity(dim, dim);
    clusters.push_back({mean, 0.5 * (cov + cov.transpose()), dist / cnt, cnt});
  }
  if (clusters.empty()) throw std::invalid_argument("train_hmm: every cluster too small");
  std::stable_sort(clusters.begin(), clusters.end(), [](const auto& a, const auto& b) { return a.distance > b.distance; });

  std::vector<HmmState> states;
  double state_first = 0.0;
  for (const auto& c : clusters) {
    if (states.empty() || state_first - c.distance > o.state_distance_gap) {
      states.push_back(HmmState{});
      state_first = c.distance;
    }
    states.back().components.emplace_back(c.mean, c.cov);
    states.back().weights.push_back(0.0);
    states.back().distance += c.distance;
  }
  for (auto& s : states) {
    s.distance /= static_cast<double>(s.components.size());
    for (auto& w : s.weights) w = 1.0 / static_cast<double>(s.weights.size());  // M_mix uniform
  }
  const auto q = static_cast<Eigen::Index>(states.size());
  Hmm hmm(std::move(states), Eigen::VectorXd::Constant(q, 1.0 / q), Eigen::MatrixXd::Constant(q, q, 1.0 / q));
  std::vector<Sequence> seqs;
  for (const auto& s : sequences) {
    Sequence v;
    for (const auto& ob : s) v.push_back(ob.features);
    if (!v.empty()) seqs.push_back(std::move(v));
  }
  auto hist = hmm.baum_welch(seqs, o.em_iterations, o.em_tolerance);
  if (em_ll) *em_ll = std::move(hist);
  hmm.floor_probabilities(o.probability_floor);
  return hmm;
}

}  // namespace rgnav::gateway_detector
