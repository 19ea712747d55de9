#include "sim/protocol_laser.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace rgnav::sim {

namespace {

// The LMS 2xx's largest measuring range (80 m mode: 8183 cm); the emulator reports anything
// beyond what the configured units can code as "no return".
constexpr double kLmsMaxRange = 81.83;

}  // namespace

std::vector<double> cast_beams(const Scene& scene, const LaserSceneState& state, const Pose2& lp, double angle_min,
                               double increment, int count, double mount_height, double max_range)
{
  const HeightBand band{mount_height, mount_height};
  const Vec2 o(lp.x, lp.y);
  std::vector<double> out(static_cast<size_t>(std::max(count, 0)));
  for (size_t i = 0; i < out.size(); ++i) {
    const double a = lp.theta + angle_min + static_cast<double>(i) * increment;
    const Vec2 d(std::cos(a), std::sin(a));
    double r = scene.cast(o, d, max_range, band, state.door_open).range;
    for (const auto& p : state.people) r = std::min(r, ray_circle(o, d, p.center, p.radius));
    out[i] = r <= max_range ? r : std::numeric_limits<double>::infinity();
  }
  return out;
}

SimScanSource::SimScanSource(const Scene& scene, const Lms2xxOptions& laser, Rng rng,
                             std::chrono::microseconds history)
    : scene_(scene), model_(laser, rng), noise_sigma_(laser.noise_sigma), history_us_(history.count()), rng_(rng)
{
}

void SimScanSource::record(LaserSceneState state)
{
  std::lock_guard<std::mutex> lock(mutex_);
  // Keep one state older than the window so a request at its edge still finds its neighbour.
  while (states_.size() > 1 && states_[1].utime < state.utime - history_us_) states_.pop_front();
  states_.push_back(std::move(state));
}

void SimScanSource::record(const Simulator& sim)
{
  record(LaserSceneState{sim.now_utime(), sim.truth(), sim.doors_open(), sim.people()});
}

LaserSceneState SimScanSource::state_at(int64_t utime) const
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (states_.empty()) return {};
  // Recorded in time order: the first state at or after utime, or its predecessor if nearer.
  auto it = std::lower_bound(states_.begin(), states_.end(), utime,
                             [](const LaserSceneState& s, int64_t t) { return s.utime < t; });
  if (it == states_.end()) return states_.back();
  if (it != states_.begin() && utime - std::prev(it)->utime < it->utime - utime) --it;
  return *it;
}

std::vector<float> SimScanSource::ranges(const drivers::sick::ScanRequest& request)
{
  const LaserSceneState state = state_at(request.utime);
  const auto truth = cast_beams(scene_, state, model_.laser_pose(state.world_from_base), request.angle_min_rad,
                                request.angle_increment_rad, request.count, model_.options().mount_height,
                                kLmsMaxRange);
  std::vector<float> out(truth.size());
  std::lock_guard<std::mutex> lock(mutex_);
  ++served_;
  for (size_t i = 0; i < truth.size(); ++i) {
    // Drawn for every beam, hit or not, as in direct mode.
    const double noise = rng_.normal(noise_sigma_);
    out[i] = std::isfinite(truth[i]) ? static_cast<float>(std::max(0.0, truth[i] + noise))
                                     : std::numeric_limits<float>::infinity();
  }
  return out;
}

uint64_t SimScanSource::scans_served() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return served_;
}

}  // namespace rgnav::sim
