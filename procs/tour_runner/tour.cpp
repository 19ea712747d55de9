#include "procs/tour_runner/tour.h"

#include <cmath>

#include "config/config.h"

namespace rgnav::tour_runner {

Tour load_tour(const std::string& path)
{
  const auto cfg = config::Config::load(path);
  Tour t;
  const auto s = cfg.numbers("start", {0, 0, 0}, -1e5, 1e5, 3, 3);
  t.world_from_start = geometry::Pose2(s[0], s[1], s[2]);
  const YAML::Node root = YAML::LoadFile(path);  // `tour` is a list of pairs, read it directly
  const YAML::Node points = root["tour"];
  if (!points || !points.IsSequence() || points.size() == 0) cfg.fail("tour", "expected a non-empty list of [x, y]");
  if (points[0].IsScalar()) {
    // The world format's flat form [x0, y0, x1, y1, ...] (drivers/sim, sim_tour).
    const auto flat = cfg.numbers("tour", {}, -1e5, 1e5, 2);
    if (flat.size() % 2) cfg.fail("tour", "flat list needs an even count of numbers");
    for (size_t i = 0; i < flat.size(); i += 2) t.world_points.emplace_back(flat[i], flat[i + 1]);
    return t;
  }
  for (size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    double x = 0, y = 0;
    if (!p.IsSequence() || p.size() != 2 || !YAML::convert<double>::decode(p[0], x) ||
        !YAML::convert<double>::decode(p[1], y) || !std::isfinite(x) || !std::isfinite(y))
      cfg.fail("tour[" + std::to_string(i) + "]", "expected [x, y] in metres");
    t.world_points.emplace_back(x, y);
  }
  return t;
}

std::vector<Eigen::Vector2d> densify(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& from,
                                     double max_spacing)
{
  std::vector<Eigen::Vector2d> out;
  Eigen::Vector2d prev = from;
  for (const auto& p : points) {
    const double d = (p - prev).norm();
    const int pieces = std::max(1, static_cast<int>(std::ceil(d / max_spacing)));
    for (int k = 1; k <= pieces; ++k) out.push_back(prev + (p - prev) * (static_cast<double>(k) / pieces));
    prev = p;
  }
  return out;
}

}  // namespace rgnav::tour_runner
