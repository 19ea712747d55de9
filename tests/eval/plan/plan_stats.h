// Small measures of the planning benchmark, beside the localization benchmark's percentile()
// and number_or_null() (bench_stats.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace rgnav::plan_eval {

inline double mean(const std::vector<double>& v)
{
  if (v.empty()) return NAN;
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}
inline double max_of(const std::vector<double>& v) { return v.empty() ? NAN : *std::max_element(v.begin(), v.end()); }
inline double min_of(const std::vector<double>& v) { return v.empty() ? NAN : *std::min_element(v.begin(), v.end()); }

}  // namespace rgnav::plan_eval
