// Fresnel integrals and the integrals of cos/sin of a quadratic phase that give the shape of
// a clothoid (curvature linear in arc length). Two independent methods, so each checks the
// other in tests: the classic Fresnel functions (series + continued fraction, accurate to
// ~1e-15) and composite Gauss-Legendre quadrature (used where the Fresnel route would lose
// precision: curvature almost constant, where the shifted arguments become huge).
#pragma once

#include <Eigen/Core>

namespace rgnav::trajectory {

struct FresnelValues
{
  double c = 0.0;  // C(x) = integral_0^x cos(pi t^2 / 2) dt
  double s = 0.0;  // S(x) = integral_0^x sin(pi t^2 / 2) dt
};

// Normalised Fresnel integrals (Numerical Recipes' algorithm in double precision: power
// series for |x| <= 1.5, complex continued fraction by the modified Lentz method beyond).
FresnelValues fresnel(double x);

// Displacement after arc length s of a curve that starts at the origin heading along +x with
// curvature kappa0 and sharpness dkappa (kappa(u) = kappa0 + dkappa * u):
//   integral_0^s (cos, sin)(kappa0 u + dkappa u^2 / 2) du.
Eigen::Vector2d clothoid_displacement(double kappa0, double dkappa, double s);

// The same by quadrature only (reference and fallback).
Eigen::Vector2d clothoid_displacement_quadrature(double kappa0, double dkappa, double s);

// integral_0^1 (cos, sin)(a t^2 / 2 + b t + c) dt and, optionally, the integrals with the
// extra factor t^2 - t (the derivative the G1 clothoid fit needs). By quadrature.
struct PhaseIntegrals
{
  double x = 0.0, y = 0.0;    // cos and sin integrals
  double dx = 0.0, dy = 0.0;  // with the factor (t^2 - t)
};
PhaseIntegrals phase_integrals(double a, double b, double c);

}  // namespace rgnav::trajectory
