// SplineAxisMapping: the mapping from a spline's control points (the mechanical DOFs) down to
// the axis of its visual model, x_k = P(s_k) = Σ_i b_i(s_k) q_i at fixed abscissas s_k (paper
// eq. 1). Linear in q with the constant Jacobian W ⊗ I₃, W_ki = b_i(s_k), so apply, applyJ,
// applyJT and jacobian are exact and cost O(m) for m samples (each row has degree + 1 entries).
// It also maps the tangents P'(s_k) = Σ_i b'_i(s_k) q_i with the derivative weights W'_ki =
// b'_i(s_k), and the second derivatives P''(s_k) with W''_ki = b''_i(s_k), which the skin needs
// for its frames and normals (generalized_cylinder.hpp).
#pragma once

#include <vector>

#include "filum/geometry/spline_point_mapping.hpp"

namespace filum::visual {

/// geometry::SplinePointMapping (positions, velocities, forces and the Jacobian W ⊗ I₃) plus
/// the tangents and second derivatives at the same abscissas.
class SplineAxisMapping final : public geometry::SplinePointMapping {
 public:
  /// abscissas in [0, 1] (any order; the skin passes them increasing), on `strand` (the whole
  /// curve by default; one strand of a cut curve: SplinePointMapping).
  SplineAxisMapping(const CurveBasis& basis, std::vector<double> abscissas, Strand strand = {});

  std::string typeName() const override { return "SplineAxisMapping"; }

  /// out = W' q: the derivatives P'(s_k) = dP/ds (not normalised; outputCount × 3).
  void applyDerivative(ConstPointsRef in, PointsRef out) const { out.noalias() = derivative_weights_ * in; }
  /// out = W'' q: the second derivatives P''(s_k) = d²P/ds² (outputCount × 3).
  void applySecondDerivative(ConstPointsRef in, PointsRef out) const { out.noalias() = second_weights_ * in; }

 private:
  SparseMatrix derivative_weights_;  // W' (m × n), b'_i(s_k)
  SparseMatrix second_weights_;      // W'' (m × n), b''_i(s_k)
};

}  // namespace filum::visual
