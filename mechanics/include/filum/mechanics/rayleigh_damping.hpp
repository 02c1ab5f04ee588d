// RayleighDamping: stiffness-proportional damping (the β K part of Rayleigh's C = α M + β K; the
// α M part is ViscousDamping). With K(q) = ∂Q/∂q the stiffness of the body's elastic force fields
// (every other force field of the same body except dampers) at the current positions,
//   Q = β K(q) q̇,
// which damps each vibration mode of frequency ω at the rate ζ = β ω / 2: high modes much more
// than low ones, rigid motions not at all (K is evaluated at q, so it rotates with the thread).
// Dissipation: Q·q̇ = β q̇ᵀ K q̇ <= 0 wherever K is negative semi-definite (a convex energy, e.g.
// a thread in tension); a compressed thread's K has positive directions, along which this term
// would feed energy back (at most β |λ_max(K)| |q̇|²).
// Jacobian: ∂Q/∂q̇ = β K(q), and ∂Q/∂q = β ∂(K(q) q̇)/∂q from the third derivatives of the
// energies, for the fields that provide them (StiffnessDerivative: GreenLagrangeStretching,
// ParametricBending). For the others (CurvatureBending, GlobalStretching, SpringForceField) that
// part of ∂Q/∂q is left out: Newton then converges linearly instead of quadratically when
// velocities are large (the solution it converges to is unchanged).
// K(q) is computed once per state, as a block band (BlockBandMatrix): the force and the Jacobian
// at the same state share it.
// Its Jacobian ∂Q/∂q̇ = β K is copied symmetrised, (K + Kᵀ)/2, as the step matrix symmetrises
// every term anyway.
// "stiffness_update": "per_step" (for implicit steps) lags K: it is computed at the first state
// evaluated in a step (after beginStep) and kept for the other evaluations at that time (the
// iterations of one implicit step; a halved step's sub-steps are at other times):
// Q = β K(q_first) q̇. It differs from the exact force by β (K(q) − K(q_first)) q̇ = O(h), within
// backward Euler's first-order error, and is linear in q̇ with ∂Q/∂q = 0, so a linearized step is
// exact for it: one Jacobian of the elastic fields per step instead of one per evaluation, and no
// third derivatives. Not for explicit multistage schemes (RK4 evaluates two stages at t + h/2).
#pragma once

#include <memory>
#include <vector>

#include "filum/core/force_field.hpp"
#include "filum/core/params.hpp"
#include "filum/mechanics/block_band_matrix.hpp"

namespace filum::mechanics {

class RayleighDamping final : public ForceField {
 public:
  /// stiffness_coefficient β (s) >= 0.
  explicit RayleighDamping(double stiffness_coefficient, bool per_step = false)
      : beta_(stiffness_coefficient), per_step_(per_step) {}
  /// "stiffness_coefficient": β (s); "stiffness_update": "per_state" (default) or "per_step".
  static std::unique_ptr<RayleighDamping> fromParams(const Params& p);

  std::string typeName() const override { return "RayleighDamping"; }
  void beginStep(const SceneState& /*s*/, double /*h*/) override { stiffness_valid_ = false; }
  void addForce(const SceneState& s, VecX& B) const override;
  void addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const override;
  bool hasJacobian() const override { return true; }

  double stiffnessCoefficient() const { return beta_; }

 private:
  void init(const Scene& scene) override;
  /// The elastic force fields of the body (resolved on first use: all fields are bound by then).
  const std::vector<const ForceField*>& elasticFields() const;
  /// K(q) of the elastic fields (k_factor 1) as a block band, recomputed only when the body's
  /// positions or velocities change.
  const BlockBandMatrix& stiffness(const SceneState& s) const;

  double beta_;
  bool per_step_ = false;  // K lagged: once per time (see above)
  const Scene* scene_ = nullptr;
  mutable bool resolved_ = false;
  mutable std::vector<const ForceField*> elastic_;
  mutable BlockBandMatrix stiffness_;  // K(q) at the state stiffness_key_
  mutable VecX stiffness_key_;  // per_state: this body's q then q̇ when K was computed (2 · 3n)
  mutable bool stiffness_valid_ = false;
  mutable double stiffness_time_ = 0.0;  // per_step: the time K was computed at
};

}  // namespace filum::mechanics
