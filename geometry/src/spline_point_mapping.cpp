#include "filum/geometry/spline_point_mapping.hpp"

namespace filum::geometry {

SplinePointMapping::SplinePointMapping(const CurveBasis& basis, std::vector<double> abscissas, Strand strand)
    : abscissas_(std::move(abscissas)), strand_(strand) {
  std::vector<Eigen::Triplet<double>> entries;
  geometry::BasisRow row;
  for (std::size_t k = 0; k < abscissas_.size(); ++k) {
    evaluateOnStrand(basis, strand_, abscissas_[k], row);
    for (int j = 0; j < row.count; ++j) entries.emplace_back(static_cast<int>(k), row.first + j, row.value[j]);
  }
  weights_.resize(static_cast<Eigen::Index>(abscissas_.size()), basis.controlPointCount());
  weights_.setFromTriplets(entries.begin(), entries.end());
}

SparseMatrix SplinePointMapping::jacobian(ConstPointsRef) const {
  // J = W ⊗ I₃ with coordinates interleaved (x y z per point).
  std::vector<Eigen::Triplet<double>> entries;
  for (int k = 0; k < weights_.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(weights_, k); it; ++it)
      for (int c = 0; c < 3; ++c)
        entries.emplace_back(3 * k + c, 3 * static_cast<int>(it.col()) + c, it.value());
  SparseMatrix J(3 * outputCount(), 3 * inputCount());
  J.setFromTriplets(entries.begin(), entries.end());
  return J;
}

std::vector<double> uniformAbscissas(int count) {
  std::vector<double> s(count);
  for (int k = 0; k < count; ++k) s[k] = static_cast<double>(k) / (count - 1);
  s.back() = 1.0;
  return s;
}

}  // namespace filum::geometry
