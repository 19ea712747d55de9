// The q-quantile of a sample (nearest rank, rounded; 0 for none): the vision benchmarks' one
// definition, so their p50 and p95 figures mean the same thing.
#pragma once

#include <algorithm>
#include <vector>

namespace rgnav::bench {

inline double percentile(std::vector<double> v, double q)
{
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5))];
}

}  // namespace rgnav::bench
