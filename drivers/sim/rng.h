// A small seeded random source owned by each simulated component (no global state). The
// generator (splitmix64) and the normal sampler (Box-Muller) are written out here rather
// than taken from <random>, whose distributions differ between standard libraries: the same
// seed gives the same numbers on every platform.
#pragma once

#include <cmath>
#include <cstdint>

namespace rgnav::sim {

class Rng
{
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}

  // Independent stream for a component: the same seed and salt give the same stream.
  // splitmix64 walks one cycle in fixed strides, so streams must start at hashed, not
  // neighbouring, points of it (neighbours would replay each other's numbers).
  static Rng derive(uint64_t seed, uint64_t salt)
  {
    Rng s(salt);
    Rng t(seed ^ s.next_u64());
    return Rng(t.next_u64());
  }

  uint64_t next_u64()
  {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1).
  double uniform() { return static_cast<double>(next_u64() >> 11) * (1.0 / 9007199254740992.0); }
  double normal(double sigma)
  {
    if (sigma <= 0.0) return 0.0;
    if (has_spare_) {
      has_spare_ = false;
      return spare_ * sigma;
    }
    double u1 = uniform();
    while (u1 <= 0.0) u1 = uniform();
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * M_PI * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * M_PI * u2) * sigma;
  }

 private:
  uint64_t state_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace rgnav::sim
