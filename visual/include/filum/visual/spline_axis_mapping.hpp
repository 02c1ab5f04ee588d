// SplineAxisMapping: the mapping from a spline's control points (the mechanical DOFs) down to
// the axis of its visual model, x_k = P(s_k) = Σ_i b_i(s_k) q_i at fixed abscissas s_k (paper
// eq. 1). Linear in q with the constant Jacobian W ⊗ I₃, W_ki = b_i(s_k), so apply, applyJ,
// applyJT and jacobian are exact and cost O(m) for m samples (each row has degree + 1 entries).
// It also maps the tangents P'(s_k) = Σ_i b'_i(s_k) q_i with the derivative weights W'_ki =
// b'_i(s_k), and the second derivatives P''(s_k) with W''_ki = b''_i(s_k), which the skin needs
// for its frames and normals (generalized_cylinder.hpp).
#pragma once

#include <vector>

#include "filum/core/mapping.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::visual {

class SplineAxisMapping final : public Mapping {
 public:
  /// abscissas in [0, 1] (any order; the skin passes them increasing).
  SplineAxisMapping(const geometry::SplineBasis& basis, std::vector<double> abscissas);

  std::string typeName() const override { return "SplineAxisMapping"; }
  int inputCount() const override { return static_cast<int>(weights_.cols()); }
  int outputCount() const override { return static_cast<int>(weights_.rows()); }
  /// out = W q: the axis points P(s_k) (outputCount × 3).
  void apply(ConstPointsRef in, PointsRef out) const override { out.noalias() = weights_ * in; }
  void applyJ(ConstPointsRef, ConstPointsRef v_in, PointsRef v_out) const override {
    v_out.noalias() = weights_ * v_in;
  }
  void applyJT(ConstPointsRef, ConstPointsRef f_out, PointsRef f_in) const override {
    f_in.noalias() += weights_.transpose() * f_out;
  }
  SparseMatrix jacobian(ConstPointsRef in) const override;

  /// out = W' q: the derivatives P'(s_k) = dP/ds (not normalised; outputCount × 3).
  void applyDerivative(ConstPointsRef in, PointsRef out) const { out.noalias() = derivative_weights_ * in; }
  /// out = W'' q: the second derivatives P''(s_k) = d²P/ds² (outputCount × 3).
  void applySecondDerivative(ConstPointsRef in, PointsRef out) const { out.noalias() = second_weights_ * in; }

  const std::vector<double>& abscissas() const { return abscissas_; }

 private:
  std::vector<double> abscissas_;
  SparseMatrix weights_;             // W  (m × n), b_i(s_k)
  SparseMatrix derivative_weights_;  // W' (m × n), b'_i(s_k)
  SparseMatrix second_weights_;      // W'' (m × n), b''_i(s_k)
};

}  // namespace filum::visual
