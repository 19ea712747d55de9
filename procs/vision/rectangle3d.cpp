#include "vision/rectangle3d.h"

#include <Eigen/Geometry>
#include <unsupported/Eigen/NonLinearOptimization>
#include <unsupported/Eigen/NumericalDiff>

#include <cmath>
#include <vector>

namespace rgnav::vision {
namespace {

Eigen::Vector3d homogeneous(const Eigen::Vector2d& p, const Pinhole& c)
{
  // Principal point at the origin (diss. 3.3.2, step 1), so that C = diag(fx, fy, 1).
  return {p.x() - c.cx, p.y() - c.cy, 1.0};
}

}  // namespace

std::array<double, 4> internal_angles(const Quadrangle& q)
{
  std::array<double, 4> a{};
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d u = q[(i + 3) % 4] - q[i], v = q[(i + 1) % 4] - q[i];
    a[i] = std::atan2(std::fabs(u.x() * v.y() - u.y() * v.x()), u.dot(v));
  }
  return a;
}

std::optional<Eigen::Vector3d> plane_normal(const Quadrangle& q, const Pinhole& camera)
{
  std::array<Eigen::Vector3d, 4> p;
  for (int i = 0; i < 4; ++i) p[i] = homogeneous(q[i], camera);
  // Sides as lines (cross product of their end points), normalised so that the products of
  // nearly parallel sides keep their precision.
  std::array<Eigen::Vector3d, 4> side;
  for (int i = 0; i < 4; ++i) {
    side[i] = p[i].cross(p[(i + 1) % 4]);
    if (side[i].norm() < 1e-12) return std::nullopt;
    side[i].normalize();
  }
  // Opposite sides 0-1 / 2-3 and 1-2 / 3-0 meet in the two vanishing points (at infinity when
  // they are parallel in the image: the homogeneous form keeps them).
  Eigen::Vector3d v1 = side[0].cross(side[2]), v2 = side[1].cross(side[3]);
  if (v1.norm() < 1e-15 || v2.norm() < 1e-15) return std::nullopt;
  v1.normalize();
  v2.normalize();
  const Eigen::Vector3d vanishing_line = v1.cross(v2);
  if (vanishing_line.norm() < 1e-15) return std::nullopt;  // both at the same point: a triangle, a line
  Eigen::Vector3d n(camera.fx * vanishing_line.x(), camera.fy * vanishing_line.y(), vanishing_line.z());  // C^T l
  n.normalize();
  // Toward the camera: the plane's points (along the rays) lie in front, at n·X < 0.
  const Eigen::Vector3d centre_ray = (camera.ray(q[0]) + camera.ray(q[1]) + camera.ray(q[2]) + camera.ray(q[3])) / 4.0;
  if (n.dot(centre_ray) > 0.0) n = -n;
  return n;
}

std::optional<Rectangle3d> intersect_rays(const Quadrangle& q, const Pinhole& camera, const Eigen::Vector3d& normal,
                                          const std::array<std::optional<Eigen::Vector3d>, 4>& measured)
{
  std::array<Eigen::Vector3d, 4> ray;
  for (int i = 0; i < 4; ++i) ray[i] = camera.ray(q[i]);
  // The plane: n·X = d (d < 0: in front of the camera, n toward it). Each measured corner,
  // moved orthogonally onto its own ray (it need not lie on it), gives one d.
  double d_sum = 0.0;
  int n_measured = 0;
  for (int i = 0; i < 4; ++i) {
    if (!measured[i] || !measured[i]->allFinite()) continue;
    const double lambda = measured[i]->dot(ray[i]) / ray[i].squaredNorm();
    if (lambda <= 0.0) continue;  // behind the camera: no measurement of this corner
    d_sum += normal.dot(lambda * ray[i]);
    ++n_measured;
  }
  if (n_measured == 0) return std::nullopt;
  return intersect_plane(q, camera, normal, d_sum / n_measured);
}

std::optional<Rectangle3d> intersect_plane(const Quadrangle& q, const Pinhole& camera, const Eigen::Vector3d& normal, double d)
{
  std::array<Eigen::Vector3d, 4> ray;
  for (int i = 0; i < 4; ++i) ray[i] = camera.ray(q[i]);
  Rectangle3d r;
  r.normal = normal;
  for (int i = 0; i < 4; ++i) {
    const double denom = normal.dot(ray[i]);
    if (std::fabs(denom) < 1e-9) return std::nullopt;  // the ray runs along the plane
    const double lambda = d / denom;
    if (lambda <= 0.0) return std::nullopt;  // the plane meets the ray behind the camera
    r.corners[i] = lambda * ray[i];
  }
  r.side_a = 0.5 * ((r.corners[1] - r.corners[0]).norm() + (r.corners[2] - r.corners[3]).norm());
  r.side_b = 0.5 * ((r.corners[2] - r.corners[1]).norm() + (r.corners[3] - r.corners[0]).norm());
  return r;
}

std::optional<Rectangle3d> reconstruct_rectangle(const Quadrangle& q, const Pinhole& camera,
                                                 const std::array<std::optional<Eigen::Vector3d>, 4>& measured)
{
  const auto n = plane_normal(q, camera);
  if (!n) return std::nullopt;
  return intersect_rays(q, camera, *n, measured);
}

namespace {

// x = [centre (3), rotation vector (3) applied to the initial orientation, width, height].
struct RectangleModel
{
  Eigen::Matrix3d r0;  // initial orientation: columns along width, height, normal
  std::array<Eigen::Vector3d, 4> corners(const Eigen::VectorXd& x) const
  {
    const Eigen::Vector3d rv = x.segment<3>(3);
    const double angle = rv.norm();
    const Eigen::Matrix3d r =
        r0 * (angle < 1e-12 ? Eigen::Matrix3d::Identity() : Eigen::AngleAxisd(angle, rv / angle).toRotationMatrix());
    const Eigen::Vector3d c = x.head<3>();
    const double w = x(6) / 2, h = x(7) / 2;
    return {c + r * Eigen::Vector3d(-w, -h, 0), c + r * Eigen::Vector3d(w, -h, 0), c + r * Eigen::Vector3d(w, h, 0),
            c + r * Eigen::Vector3d(-w, h, 0)};
  }
};

struct FitResiduals
{
  using Scalar = double;
  enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };
  using InputType = Eigen::VectorXd;
  using ValueType = Eigen::VectorXd;
  using JacobianType = Eigen::MatrixXd;

  RectangleModel model;
  Quadrangle q;
  Pinhole camera;
  std::vector<std::pair<int, double>> depths;  // corner, measured z
  std::vector<double> sigma_z;
  double sigma_px = 0.5;

  int inputs() const { return 8; }
  int values() const { return 8 + static_cast<int>(depths.size()); }
  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& f) const
  {
    const auto c = model.corners(x);
    for (int i = 0; i < 4; ++i) {
      // Behind or at the camera: a large residual (the fit must not go there).
      const Eigen::Vector2d p = c[i].z() > 1e-3 ? camera.project(c[i]) : Eigen::Vector2d(1e6, 1e6);
      f.segment<2>(2 * i) = (p - q[i]) / sigma_px;
    }
    for (size_t k = 0; k < depths.size(); ++k)
      f(8 + static_cast<int>(k)) = (c[static_cast<size_t>(depths[k].first)].z() - depths[k].second) / sigma_z[k];
    return 0;
  }
};

}  // namespace

std::optional<Rectangle3d> refine_rectangle(const Quadrangle& q, const Pinhole& camera, const Rectangle3d& initial,
                                            const std::array<std::optional<Eigen::Vector3d>, 4>& measured,
                                            const RefineOptions& options)
{
  const auto& k = initial.corners;
  Eigen::Vector3d ex = (k[1] - k[0]) + (k[2] - k[3]), ey = (k[3] - k[0]) + (k[2] - k[1]);
  if (ex.norm() < 1e-9 || ey.norm() < 1e-9) return std::nullopt;
  ex.normalize();
  ey = (ey - ey.dot(ex) * ex).normalized();
  FitResiduals fit;
  fit.model.r0.col(0) = ex;
  fit.model.r0.col(1) = ey;
  fit.model.r0.col(2) = ex.cross(ey);
  fit.q = q;
  fit.camera = camera;
  fit.sigma_px = options.sigma_px;
  for (int i = 0; i < 4; ++i) {
    if (!measured[i] || !measured[i]->allFinite() || measured[i]->z() <= 0.0) continue;
    const double z = measured[i]->z();
    fit.depths.emplace_back(i, z);
    fit.sigma_z.push_back(std::max(1e-3, z * z * options.sigma_disparity / options.focal_baseline));
  }
  if (fit.depths.empty()) return std::nullopt;
  Eigen::VectorXd x(8);
  x << (k[0] + k[1] + k[2] + k[3]) / 4.0, Eigen::Vector3d::Zero(), initial.side_a, initial.side_b;
  Eigen::NumericalDiff<FitResiduals> numeric(fit);
  Eigen::LevenbergMarquardt<Eigen::NumericalDiff<FitResiduals>> lm(numeric);
  lm.parameters.maxfev = options.max_iterations * 9;
  const auto status = lm.minimize(x);
  if (status == Eigen::LevenbergMarquardtSpace::ImproperInputParameters || !x.allFinite()) return std::nullopt;
  Rectangle3d r;
  r.corners = fit.model.corners(x);
  for (const auto& c : r.corners)
    if (c.z() <= 0.0) return std::nullopt;
  r.side_a = std::fabs(x(6));
  r.side_b = std::fabs(x(7));
  r.normal = (r.corners[1] - r.corners[0]).cross(r.corners[3] - r.corners[0]).normalized();
  if (r.normal.dot(r.corners[0] + r.corners[2]) > 0.0) r.normal = -r.normal;
  return r;
}

}  // namespace rgnav::vision
