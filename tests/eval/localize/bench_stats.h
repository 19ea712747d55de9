// Small measures shared by the localization benchmark's trials: percentiles, the error of an
// estimate in its region's frame, and "localized and staying so".
#pragma once

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <vector>

#include "localizer/localizer.h"
#include "truth_frames.h"

namespace rgnav::localize_eval {

constexpr double kDeg = M_PI / 180.0;
constexpr double kGoodXy = 0.3, kGoodTheta = 10.0 * kDeg;   // "localized" (issue targets)
constexpr double kDivergedXy = 0.5;

inline double thread_cpu()
{
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

inline double percentile(std::vector<double> v, double q)
{
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5))];
}

inline nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// Error of an estimate against the truth, in the estimate's region frame.
struct Error
{
  double xy = 0, theta = 0;
  bool good() const { return xy <= kGoodXy && theta <= kGoodTheta; }
};
inline Error error_of(const localizer::Estimate& e, const TruthFrames& frames, const geometry::Pose2& truth)
{
  const geometry::Pose2 t = frames.in_region(e.region, truth);
  return {(e.region_from_base.translation() - t.translation()).norm(),
          std::fabs(geometry::normalize_angle(e.region_from_base.theta() - t.theta()))};
}

// "Localized and staying so": the time after which every update is good to the end.
struct Settling
{
  double last_bad_s = 0;     // time of the newest bad (or missing) estimate
  double first_good_after = NAN, distance_at = NAN;
  bool good_now = false;
  void add(double t, double distance, bool good)
  {
    if (!good) {
      last_bad_s = t;
      good_now = false;
      first_good_after = NAN;
    } else if (!good_now) {
      good_now = true;
      first_good_after = t;
      distance_at = distance;
    }
  }
};

}  // namespace rgnav::localize_eval
