#include "geometry/symmetric_eigen2.h"

#include <Eigen/Eigenvalues>

namespace rgnav::geometry {

SymmetricEigen2 symmetric_eigen(const Eigen::Matrix2d& m)
{
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(m);
  return {es.eigenvalues(), es.eigenvectors()};
}

}  // namespace rgnav::geometry
