// SplinePointMapping: points at fixed abscissas s_k of a spline, x_k = P(s_k) = Σ_i b_i(s_k) q_i
// (paper eq. 1). Linear in q: its Jacobian W ⊗ I₃ is constant, with W_ki = b_i(s_k), so forces
// F_k at the points map up to generalized forces Q_i = Σ_k b_i(s_k) F_k (paper §3;
// docs/architecture.md, "The three-sided model"). It samples a curve's points for outputs
// (polylines written by filum run); a force at a point of a body goes up through that point's
// own mapping, a BodyPoint (core/body_point.hpp).
#pragma once

#include <vector>

#include "filum/core/mapping.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::geometry {

class SplinePointMapping : public Mapping {
 public:
  /// The points at `abscissas` on `strand` (all inside it; the whole curve by default): at its
  /// end the strand's own end point, which differs from the next strand's start at a cut
  /// (CurveBasis::strands).
  SplinePointMapping(const CurveBasis& basis, std::vector<double> abscissas, Strand strand = {});

  std::string typeName() const override { return "SplinePointMapping"; }
  int inputCount() const override { return static_cast<int>(weights_.cols()); }
  int outputCount() const override { return static_cast<int>(weights_.rows()); }
  void apply(ConstPointsRef in, PointsRef out) const override { out.noalias() = weights_ * in; }
  void applyJ(ConstPointsRef, ConstPointsRef v_in, PointsRef v_out) const override {
    v_out.noalias() = weights_ * v_in;
  }
  void applyJT(ConstPointsRef, ConstPointsRef f_out, PointsRef f_in) const override {
    f_in.noalias() += weights_.transpose() * f_out;
  }
  SparseMatrix jacobian(ConstPointsRef in) const override;

  const std::vector<double>& abscissas() const { return abscissas_; }
  const Strand& strand() const { return strand_; }
  /// W (outputs × inputs): the basis values b_i(s_k).
  const SparseMatrix& weights() const { return weights_; }

 private:
  std::vector<double> abscissas_;
  Strand strand_;
  SparseMatrix weights_;
};

/// `count` abscissas equally spaced on [0, 1] (count >= 2).
std::vector<double> uniformAbscissas(int count);

}  // namespace filum::geometry
