// Resampling of the particle set: low-variance (systematic) resampling (Probabilistic Robotics
// 4.3.4) to a size chosen by KLD sampling (Fox 2003): enough particles that the sample-based
// posterior is within kld_epsilon of the true one with probability 1 - delta, given how many
// histogram bins the posterior occupies.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "localizer/localizer_options.h"

namespace rgnav::localizer {

// Particles needed for a posterior that occupies k bins.
int kld_sample_count(int k, const ParticleCount& options);

// Indices of `n` particles drawn in proportion to `weights` (need not be normalised) with one
// random offset: a particle of weight w is drawn floor(n w) or ceil(n w) times.
std::vector<size_t> low_variance_resample(const std::vector<double>& weights, size_t n, std::mt19937_64& rng);

}  // namespace rgnav::localizer
