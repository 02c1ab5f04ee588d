#include "filum/core/body_point.hpp"

namespace filum {

SparseMatrix BodyPoint::jacobian(ConstPointsRef) const {
  // J = w ⊗ I₃: row c of the point, column 3 p_j + c, value w_j.
  const PointWeights& w = weights();
  SparseMatrix J(3, 3 * inputCount());
  J.reserve(Eigen::VectorXi::Constant(3, w.count));
  for (int j = 0; j < w.count; ++j)
    for (int c = 0; c < 3; ++c) J.insert(c, 3 * w.point[j] + c) = w.weight[j];
  J.makeCompressed();
  return J;
}

}  // namespace filum
