// GlobalStretching: the paper's global approximation of the stretching energy (§3 "Deformation
// Energy", after Terzopoulos et al.):
//   Ê = ½ k (l²/l0² − 1)²,   k = E·A·l0 / 4,
// l the current length of the curve, l0 its rest length, E Young's modulus (Pa), A = π r².
// (For a small strain e = l/l0 − 1, Ê ≈ 2 k e² = ½ (E A / l0)(l − l0)²: a spring of the whole
// thread.) The paper sums the lengths of sub-sampled segments and differentiates Ê by finite
// differences; here l = ∫ |P'| ds by Gauss-Legendre per piece (the limit of the sub-sampled
// polyline) and the gradient is analytic:
//   ∂l/∂q_j = Σ_g w_g b'_j(s_g) u_g,   u_g = P'(s_g)/|P'(s_g)|,
//   Ê'(l) = 2 k (l²/l0² − 1) l / l0²,   Q_j = −Ê'(l) ∂l/∂q_j,
//   ∇²Ê = Ê''(l) ∇l ∇lᵀ + Ê'(l) Σ_g w_g b'_i b'_j (I − u_g u_gᵀ)/|P'(s_g)|,
//   Ê''(l) = 2 k ((l²/l0² − 1)/l0² + 2 l²/l0⁴).
// The first Hessian term couples every control point with every other (rank one, dense): an
// implicit step with this energy factors a full matrix (StepMatrix takes the sparse path) —
// the price of a global energy; GreenLagrangeStretching is local.
#pragma once

#include <memory>

#include "filum/core/force_field.hpp"
#include "filum/mechanics/curve_quadrature.hpp"
#include "filum/mechanics/elastic_parameters.hpp"

namespace filum::mechanics {

class GlobalStretching final : public ForceField {
 public:
  explicit GlobalStretching(ElasticParameters parameters) : parameters_(parameters) {}
  /// "youngs_modulus": Pa, "rest_length": m (default: the initial curve's length),
  /// "quadrature_nodes": per piece (default 2d − 1).
  static std::unique_ptr<GlobalStretching> fromParams(const Params& p);

  std::string typeName() const override { return "GlobalStretching"; }
  void addForce(const SceneState& s, VecX& B) const override;
  double potentialEnergy(const SceneState& s) const override;
  void addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const override;
  bool hasJacobian() const override { return true; }

  /// l(q) = Σ_g w_g |P'(s_g)| (m).
  double length(const SceneState& s) const;
  double restLength() const { return quadrature_.restLength(); }
  /// k = E A l0 / 4 (N·m).
  double stiffness() const { return k_; }

 private:
  void init(const Scene& scene) override;
  /// l, and ∂l/∂q in gradient_ (n × 3).
  double lengthAndGradient(ConstPointsRef q) const;

  ElasticParameters parameters_;
  CurveQuadrature quadrature_;
  double k_ = 0.0;
  mutable Points gradient_;  // workspace ∂l/∂q
};

}  // namespace filum::mechanics
