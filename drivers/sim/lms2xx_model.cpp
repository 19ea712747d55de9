#include "sim/lms2xx_model.h"

#include <cmath>
#include <limits>

namespace rgnav::sim {

Lms2xxModel::Lms2xxModel(const Lms2xxOptions& options, Rng rng) : options_(options), rng_(rng)
{
  for (int i = 0; i < options_.beams; ++i) {
    const double a = -M_PI / 2.0 + i * options_.angle_increment();
    directions_.emplace_back(std::cos(a), std::sin(a));
  }
}

Pose2 Lms2xxModel::laser_pose(const Pose2& base) const
{
  const Vec2 p = Vec2(base.x, base.y) + rotate({options_.mount_x, options_.mount_y}, base.theta);
  return {p.x(), p.y(), normalize_angle(base.theta + options_.mount_yaw)};
}

std::vector<double> Lms2xxModel::true_ranges(const Scene& scene, const std::vector<uint8_t>& door_open,
                                             const std::vector<Circle>& people, const Pose2& lp) const
{
  const HeightBand band{options_.mount_height, options_.mount_height};
  const Vec2 o(lp.x, lp.y);
  const double c = std::cos(lp.theta), s = std::sin(lp.theta);
  const double max_range = options_.range_max();
  std::vector<double> out(directions_.size());
  for (size_t i = 0; i < directions_.size(); ++i) {
    const Vec2& dl = directions_[i];
    const Vec2 d(c * dl.x() - s * dl.y(), s * dl.x() + c * dl.y());
    double r = scene.cast(o, d, max_range, band, door_open).range;
    for (const auto& p : people) r = std::min(r, ray_circle(o, d, p.center, p.radius));
    out[i] = r <= max_range ? r : std::numeric_limits<double>::infinity();
  }
  return out;
}

sensors::LaserScan Lms2xxModel::measure(const Scene& scene, const std::vector<uint8_t>& door_open,
                                        const std::vector<Circle>& people, const Pose2& base_pose, int64_t utime,
                                        int64_t scan_id)
{
  sensors::LaserScan scan;
  scan.utime = utime;
  scan.scan_id = scan_id;
  scan.sensor = options_.sensor;
  scan.angle_min = -M_PI / 2.0;
  scan.angle_increment = options_.angle_increment();
  scan.range_min = options_.resolution();
  scan.range_max = options_.range_max();
  scan.scan_time = options_.scan_time();
  const auto truth = true_ranges(scene, door_open, people, laser_pose(base_pose));
  const double unit = options_.resolution();
  scan.ranges.resize(truth.size());
  for (size_t i = 0; i < truth.size(); ++i) {
    // Noise is drawn for every beam, hit or not, so the random stream does not depend on
    // which beams hit something.
    const double noise = rng_.normal(options_.noise_sigma);
    if (!std::isfinite(truth[i])) {
      scan.ranges[i] = static_cast<float>(scan.range_max);
      continue;
    }
    const double units = std::max(1.0, std::round((truth[i] + noise) / unit));
    scan.ranges[i] = static_cast<float>(std::min(units * unit, scan.range_max));
  }
  return scan;
}

}  // namespace rgnav::sim
