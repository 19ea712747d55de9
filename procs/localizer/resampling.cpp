#include "localizer/resampling.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rgnav::localizer {

int kld_sample_count(int k, const ParticleCount& o)
{
  if (k <= 1) return o.min;
  const double a = 2.0 / (9.0 * (k - 1));
  const double b = 1.0 - a + std::sqrt(a) * o.kld_z;
  const double n = (k - 1) / (2.0 * o.kld_epsilon) * b * b * b;
  return std::clamp(static_cast<int>(std::ceil(n)), o.min, o.max);
}

std::vector<size_t> low_variance_resample(const std::vector<double>& weights, size_t n, std::mt19937_64& rng)
{
  std::vector<size_t> out;
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  if (weights.empty() || n == 0 || !(total > 0)) return out;
  out.reserve(n);
  const double step = total / static_cast<double>(n);
  double u = std::uniform_real_distribution<double>(0.0, step)(rng);
  double c = weights[0];
  size_t i = 0;
  for (size_t m = 0; m < n; ++m) {
    while (u > c && i + 1 < weights.size()) c += weights[++i];
    out.push_back(i);
    u += step;
  }
  return out;
}

}  // namespace rgnav::localizer
