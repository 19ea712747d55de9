#include "trajectory/fresnel.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "trajectory/gauss_legendre.h"

namespace rgnav::trajectory {

namespace {

// integral over [lo, hi] of f, by composite 10-point Gauss-Legendre with `panels` panels.
template <class F>
void gauss_legendre(double lo, double hi, int panels, F&& f)
{
  const double h = (hi - lo) / panels;
  for (int p = 0; p < panels; ++p) {
    const double mid = lo + (p + 0.5) * h, half = 0.5 * h;
    for (int i = 0; i < 5; ++i) {
      f(mid - half * kGaussLegendreX[i], half * kGaussLegendreW[i]);
      f(mid + half * kGaussLegendreX[i], half * kGaussLegendreW[i]);
    }
  }
}

// Panels so that the phase changes by at most ~0.3 rad per panel: the 10-point rule is then
// exact to machine precision for these smooth integrands.
int panels_for(double phase_change) { return std::clamp(static_cast<int>(std::ceil(phase_change / 0.3)), 1, 100000); }

}  // namespace

FresnelValues fresnel(double x)
{
  constexpr double kEps = 1e-16, kFpMin = 1e-300, kXMin = 1.5;
  constexpr int kMaxIt = 300;
  const double ax = std::fabs(x);
  FresnelValues r;
  if (ax < std::sqrt(kFpMin)) {
    r.c = ax;
    r.s = 0.0;
  } else if (ax <= kXMin) {
    // Alternating power series, summing the C and S terms in turn.
    double sum = 0.0, sums = 0.0, sumc = ax, sign = 1.0, term = ax;
    const double fact = M_PI_2 * ax * ax;
    bool odd = true;
    int n = 3;
    for (int k = 1; k <= kMaxIt; ++k) {
      term *= fact / k;
      sum += sign * term / n;
      const double test = std::fabs(sum) * kEps;
      if (odd) {
        sign = -sign;
        sums = sum;
        sum = sumc;
      } else {
        sumc = sum;
        sum = sums;
      }
      if (term < test) break;
      odd = !odd;
      n += 2;
    }
    r.c = sumc;
    r.s = sums;
  } else {
    // Continued fraction for the complementary error function (modified Lentz).
    using C = std::complex<double>;
    const double pix2 = M_PI * ax * ax;
    C b(1.0, -pix2);
    C cc(1.0 / kFpMin, 0.0);
    C d = 1.0 / b;
    C h = d;
    int n = -1;
    for (int k = 2; k <= kMaxIt; ++k) {
      n += 2;
      const double a = -n * (n + 1.0);
      b += 4.0;
      d = 1.0 / (a * d + b);
      cc = b + a / cc;
      const C del = cc * d;
      h *= del;
      if (std::fabs(del.real() - 1.0) + std::fabs(del.imag()) < kEps) break;
    }
    h *= C(ax, -ax);
    const C cs = C(0.5, 0.5) * (1.0 - C(std::cos(0.5 * pix2), std::sin(0.5 * pix2)) * h);
    r.c = cs.real();
    r.s = cs.imag();
  }
  if (x < 0) {
    r.c = -r.c;
    r.s = -r.s;
  }
  return r;
}

Eigen::Vector2d clothoid_displacement_quadrature(double kappa0, double dkappa, double s)
{
  const double phase_change = std::fabs(kappa0) * std::fabs(s) + 0.5 * std::fabs(dkappa) * s * s;
  Eigen::Vector2d sum(0, 0);
  gauss_legendre(0.0, s, panels_for(phase_change), [&](double u, double w) {
    const double th = kappa0 * u + 0.5 * dkappa * u * u;
    sum += w * Eigen::Vector2d(std::cos(th), std::sin(th));
  });
  return sum;
}

Eigen::Vector2d clothoid_displacement(double kappa0, double dkappa, double s)
{
  const double a = std::fabs(dkappa);
  const double k1 = kappa0 + dkappa * s;
  // Completing the square shifts the Fresnel arguments by kappa0 / dkappa; the phase offset
  // phi = kappa0^2 / (2 dkappa) then multiplies the rounding error of the arguments. Keep
  // the Fresnel route where phi stays moderate, quadrature elsewhere (nearly an arc).
  const double kmax = std::max(std::fabs(kappa0), std::fabs(k1));
  if (a < 1e-12 || kmax * kmax / (2.0 * a) > 1e4) return clothoid_displacement_quadrature(kappa0, dkappa, s);
  const double sigma = dkappa > 0 ? 1.0 : -1.0;
  const double scale = std::sqrt(M_PI / a);
  const double t0 = (kappa0 / dkappa) / scale * 1.0;  // sqrt(a/pi) * (0 + kappa0/dkappa)
  const double t1 = (s + kappa0 / dkappa) / scale;
  const FresnelValues f0 = fresnel(t0), f1 = fresnel(t1);
  const double dc = f1.c - f0.c, ds = f1.s - f0.s;
  const double phi = kappa0 * kappa0 / (2.0 * dkappa);
  const double cp = std::cos(phi), sp = std::sin(phi);
  return scale * Eigen::Vector2d(dc * cp + sigma * ds * sp, sigma * ds * cp - dc * sp);
}

PhaseIntegrals phase_integrals(double a, double b, double c)
{
  PhaseIntegrals r;
  const double phase_change = 0.5 * std::fabs(a) + std::fabs(b);
  gauss_legendre(0.0, 1.0, panels_for(phase_change), [&](double t, double w) {
    const double ph = 0.5 * a * t * t + b * t + c;
    const double co = std::cos(ph), si = std::sin(ph), f = t * t - t;
    r.x += w * co;
    r.y += w * si;
    r.dx += w * co * f;
    r.dy += w * si * f;
  });
  return r;
}

}  // namespace rgnav::trajectory
