#include "filum/visual/spline_axis_mapping.hpp"

namespace filum::visual {

SplineAxisMapping::SplineAxisMapping(const CurveBasis& basis, std::vector<double> abscissas, Strand strand)
    : geometry::SplinePointMapping(basis, std::move(abscissas), strand) {
  std::vector<Eigen::Triplet<double>> derivatives, seconds;
  geometry::BasisRow row;
  for (std::size_t k = 0; k < this->abscissas().size(); ++k) {
    evaluateOnStrand(basis, this->strand(), this->abscissas()[k], row);
    for (int j = 0; j < row.count; ++j) {
      derivatives.emplace_back(static_cast<int>(k), row.first + j, row.d1[j]);
      seconds.emplace_back(static_cast<int>(k), row.first + j, row.d2[j]);
    }
  }
  derivative_weights_.resize(outputCount(), basis.controlPointCount());
  derivative_weights_.setFromTriplets(derivatives.begin(), derivatives.end());
  second_weights_.resize(outputCount(), basis.controlPointCount());
  second_weights_.setFromTriplets(seconds.begin(), seconds.end());
}

}  // namespace filum::visual
