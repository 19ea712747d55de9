// Eigenvalues and eigenvectors of a symmetric 2x2 matrix (a scatter or covariance of 2D points:
// the direction of a fitted line, the normal of a surface patch, the weakest direction of a
// match). One out-of-line instance of Eigen's SelfAdjointEigenSolver for the whole tree: each
// file that instantiated it paid ~6 s of compile time at -O2, and the numbers are the solver's own.
#pragma once

#include <Eigen/Core>

namespace rgnav::geometry {

struct SymmetricEigen2
{
  Eigen::Vector2d values;   // ascending
  Eigen::Matrix2d vectors;  // column i belongs to values(i), unit length
};

SymmetricEigen2 symmetric_eigen(const Eigen::Matrix2d& m);

}  // namespace rgnav::geometry
