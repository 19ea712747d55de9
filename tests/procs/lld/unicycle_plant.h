// Test-only plant: a kinematic unicycle whose velocities follow the commands with a first-
// order lag (time constant tau), integrated in 1 ms steps along exact arcs.
#pragma once

#include <cmath>

#include "geometry/pose2.h"
#include "lld/tracking_law.h"

namespace rgnav::lld::testing {

struct UnicyclePlant
{
  geometry::Pose2 pose;
  double v = 0.0;
  double omega = 0.0;
  double tau = 0.1;  // [s]

  void advance(const VelocityCommand& cmd, double dt)
  {
    const int n = std::max(1, static_cast<int>(std::round(dt / 0.001)));
    const double h = dt / n;
    const double a = 1.0 - std::exp(-h / tau);
    for (int i = 0; i < n; ++i) {
      v += (cmd.v - v) * a;
      omega += (cmd.omega - omega) * a;
      const double ds = v * h, dth = omega * h;
      double lx = ds, ly = 0.0;
      if (std::fabs(dth) > 1e-12) {
        lx = ds * std::sin(dth) / dth;
        ly = ds * (1.0 - std::cos(dth)) / dth;
      }
      pose = pose * geometry::Pose2(lx, ly, dth);
    }
  }
};

}  // namespace rgnav::lld::testing
