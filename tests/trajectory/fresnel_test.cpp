#include "trajectory/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rgnav::trajectory {
namespace {

TEST(Fresnel, KnownValues)
{
  // Abramowitz & Stegun table 7.7 / high-precision references.
  const struct { double x, c, s; } ref[] = {
      {0.5, 0.4923442258714464, 0.0647324328599180},
      {1.0, 0.7798934003768228, 0.4382591473903548},
      {1.5, 0.4452611760398215, 0.6975049600820930},
      {2.0, 0.4882534060753408, 0.3434156783636982},
      {3.0, 0.6057207892976856, 0.4963129989673750},
      {5.0, 0.5636311887040122, 0.4991913819171169},
  };
  for (const auto& r : ref) {
    const FresnelValues f = fresnel(r.x);
    EXPECT_NEAR(f.c, r.c, 1e-13) << r.x;
    EXPECT_NEAR(f.s, r.s, 1e-13) << r.x;
    const FresnelValues g = fresnel(-r.x);
    EXPECT_DOUBLE_EQ(g.c, -f.c);
    EXPECT_DOUBLE_EQ(g.s, -f.s);
  }
  EXPECT_NEAR(fresnel(1e4).c, 0.5, 1e-4);
  EXPECT_NEAR(fresnel(1e4).s, 0.5, 1e-4);
}

TEST(Fresnel, ContinuousAtMethodSwitch)
{
  // Series just below the switch, continued fraction just above: they agree to the slope
  // times the step (|C'|, |S'| <= 1) plus rounding.
  const FresnelValues a = fresnel(1.5 - 1e-12), b = fresnel(1.5 + 1e-12);
  EXPECT_NEAR(a.c, b.c, 2e-12 + 1e-14);
  EXPECT_NEAR(a.s, b.s, 2e-12 + 1e-14);
}

TEST(Fresnel, ClothoidDisplacementMatchesQuadrature)
{
  for (double k0 : {-2.0, -0.3, 0.0, 0.01, 1.5})
    for (double dk : {-4.0, -0.5, 1e-3, 0.7, 3.0})
      for (double s : {0.1, 0.8, 2.5}) {
        const Eigen::Vector2d a = clothoid_displacement(k0, dk, s);
        const Eigen::Vector2d b = clothoid_displacement_quadrature(k0, dk, s);
        EXPECT_NEAR((a - b).norm(), 0.0, 1e-11) << k0 << " " << dk << " " << s;
      }
}

TEST(Fresnel, PureClothoidIsScaledFresnel)
{
  // kappa = c s from the origin: (x, y) = sqrt(pi / c) (C, S)(s sqrt(c / pi)).
  const double c = 2.0, s = 1.3;
  const double k = std::sqrt(M_PI / c);
  const FresnelValues f = fresnel(s / k);
  const Eigen::Vector2d d = clothoid_displacement(0.0, c, s);
  EXPECT_NEAR(d.x(), k * f.c, 1e-14);
  EXPECT_NEAR(d.y(), k * f.s, 1e-14);
}

}  // namespace
}  // namespace rgnav::trajectory
