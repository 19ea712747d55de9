#include "procs/rg_kernel/objects3d.h"

#include <algorithm>
#include <cmath>

namespace rgnav::rg_kernel {
namespace {

Eigen::Vector3d centre(const rgmap::Rectangle3d& r) { return r.corners.colwise().mean().transpose(); }

// Observations of one object, from its confidence (1 - 0.5^n after n observations).
double observations(double confidence)
{
  const double c = std::clamp(confidence, 0.0, 0.999);
  return std::max(1.0, std::log(1.0 - c) / std::log(0.5));
}

// The pairing of b's corners with a's (around either way, any start) that brings them nearest.
Eigen::Matrix<double, 4, 3> paired(const rgmap::Rectangle3d& a, const rgmap::Rectangle3d& b)
{
  Eigen::Matrix<double, 4, 3> best = b.corners;
  double best_sum = 1e18;
  for (const int dir : {1, -1})
    for (int shift = 0; shift < 4; ++shift) {
      Eigen::Matrix<double, 4, 3> m;
      for (int i = 0; i < 4; ++i) m.row(i) = b.corners.row(((shift + dir * i) % 4 + 4) % 4);
      const double sum = (m - a.corners).rowwise().norm().sum();
      if (sum < best_sum) {
        best_sum = sum;
        best = m;
      }
    }
  return best;
}

bool same_object(const rgmap::Rectangle3d& a, const rgmap::Rectangle3d& b, const Objects3dOptions& o)
{
  if (a.kind != b.kind) return false;
  if ((centre(a) - centre(b)).norm() > o.match_distance) return false;
  if (std::fabs(a.normal.dot(b.normal)) < std::cos(o.match_angle_deg * M_PI / 180.0)) return false;
  auto close = [&](double x, double y) { return std::fabs(x - y) <= o.match_size_ratio * std::max(x, y); };
  return close(a.width, b.width) && close(a.height, b.height);
}

}  // namespace

std::vector<rgmap::Rectangle3d> to_region_frame(const std::vector<rgmap::Rectangle3d>& in_map,
                                                const geometry::Pose2& map_from_region)
{
  std::vector<rgmap::Rectangle3d> out;
  out.reserve(in_map.size());
  for (const auto& r : in_map) out.push_back(rgmap::moved(r, map_from_region.inverse()));
  return out;
}

void merge_objects3d(std::vector<rgmap::Rectangle3d>* objects, const std::vector<rgmap::Rectangle3d>& observed,
                     int64_t* next_id, const Objects3dOptions& o)
{
  if (!o.enabled) return;
  for (const auto& obs : observed) {
    auto it = std::find_if(objects->begin(), objects->end(), [&](const rgmap::Rectangle3d& k) { return same_object(k, obs, o); });
    if (it == objects->end()) {
      rgmap::Rectangle3d fresh = obs;
      fresh.id = (*next_id)++;
      fresh.confidence = 0.5;
      objects->push_back(fresh);
      continue;
    }
    // The running average of the observations' corners, sides and normal.
    const double n = observations(it->confidence);
    const double w = 1.0 / (n + 1.0);
    it->corners = (1.0 - w) * it->corners + w * paired(*it, obs);
    it->width = (1.0 - w) * it->width + w * obs.width;
    it->height = (1.0 - w) * it->height + w * obs.height;
    const Eigen::Vector3d nrm = obs.normal.dot(it->normal) >= 0.0 ? obs.normal : Eigen::Vector3d(-obs.normal);
    it->normal = ((1.0 - w) * it->normal + w * nrm).normalized();
    it->confidence = 1.0 - std::pow(0.5, n + 1.0);
  }
  if (objects->size() > static_cast<size_t>(o.max_per_region)) {
    std::stable_sort(objects->begin(), objects->end(),
                     [](const rgmap::Rectangle3d& a, const rgmap::Rectangle3d& b) { return a.confidence > b.confidence; });
    objects->resize(static_cast<size_t>(o.max_per_region));
  }
}

}  // namespace rgnav::rg_kernel
