#include "gateway_detector/door_confirmation.h"

#include <cmath>

namespace rgnav::gateway_detector {

std::optional<std::array<Vec2, 2>> door_edges(const Rectangle3& r, const DoorConfirmationOptions& o)
{
  if (r.width < o.min_width || r.width > o.max_width) return std::nullopt;
  if (r.height < o.min_height || r.height > o.max_height) return std::nullopt;
  const double nn = r.normal.norm();
  if (!(nn > 0) || std::fabs(r.normal.z()) / nn > o.max_normal_z) return std::nullopt;
  // The vertical edges are the two opposite edges most aligned with z.
  auto verticality = [&](int i) {
    const Eigen::Vector3d e = r.corners[(i + 1) % 4] - r.corners[i];
    return e.norm() > 0 ? std::fabs(e.z()) / e.norm() : 0.0;
  };
  const int first = verticality(0) + verticality(2) >= verticality(1) + verticality(3) ? 0 : 1;
  std::array<Vec2, 2> edges;
  for (int k = 0; k < 2; ++k) {
    const int i = first + 2 * k;
    const Eigen::Vector3d m = 0.5 * (r.corners[i] + r.corners[(i + 1) % 4]);
    edges[static_cast<size_t>(k)] = Vec2(m.x(), m.y());
  }
  return edges;
}

bool edges_match(const std::array<Vec2, 2>& e, const Vec2& a, const Vec2& b, double tol)
{
  return ((e[0] - a).norm() < tol && (e[1] - b).norm() < tol) || ((e[0] - b).norm() < tol && (e[1] - a).norm() < tol);
}

}  // namespace rgnav::gateway_detector
