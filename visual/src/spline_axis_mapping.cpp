#include "filum/visual/spline_axis_mapping.hpp"

namespace filum::visual {

SplineAxisMapping::SplineAxisMapping(const geometry::SplineBasis& basis, std::vector<double> abscissas)
    : abscissas_(std::move(abscissas)) {
  std::vector<Eigen::Triplet<double>> values, derivatives, seconds;
  geometry::BasisRow row;
  for (std::size_t k = 0; k < abscissas_.size(); ++k) {
    basis.evaluate(abscissas_[k], row);
    for (int j = 0; j < row.count; ++j) {
      values.emplace_back(static_cast<int>(k), row.first + j, row.value[j]);
      derivatives.emplace_back(static_cast<int>(k), row.first + j, row.d1[j]);
      seconds.emplace_back(static_cast<int>(k), row.first + j, row.d2[j]);
    }
  }
  const auto m = static_cast<Eigen::Index>(abscissas_.size());
  weights_.resize(m, basis.controlPointCount());
  weights_.setFromTriplets(values.begin(), values.end());
  derivative_weights_.resize(m, basis.controlPointCount());
  derivative_weights_.setFromTriplets(derivatives.begin(), derivatives.end());
  second_weights_.resize(m, basis.controlPointCount());
  second_weights_.setFromTriplets(seconds.begin(), seconds.end());
}

SparseMatrix SplineAxisMapping::jacobian(ConstPointsRef) const {
  // J = W ⊗ I₃, coordinates interleaved (x y z per point).
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(3 * weights_.nonZeros());
  for (int k = 0; k < weights_.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(weights_, k); it; ++it)
      for (int c = 0; c < 3; ++c) entries.emplace_back(3 * k + c, 3 * static_cast<int>(it.col()) + c, it.value());
  SparseMatrix J(3 * outputCount(), 3 * inputCount());
  J.setFromTriplets(entries.begin(), entries.end());
  return J;
}

}  // namespace filum::visual
