// 10-point Gauss-Legendre quadrature on [-1, 1]: the five positive nodes and their weights (the
// rule is symmetric: -x has the same weight). Shared by the clothoid integrals (fresnel.cpp) and
// the conic arc length (segment.cpp).
#pragma once

namespace rgnav::trajectory {

inline constexpr double kGaussLegendreX[5] = {0.1488743389816312, 0.4333953941292472, 0.6794095682990244,
                                              0.8650633666889845, 0.9739065285171717};
inline constexpr double kGaussLegendreW[5] = {0.2955242247147529, 0.2692667193099963, 0.2190863625159820,
                                              0.1494513491505806, 0.0666713443086881};

}  // namespace rgnav::trajectory
