// ViscousDamping: a drag proportional to the velocity of every point of the curve,
// f(s) = −γ m Ṗ(s) per unit of parameter, whose generalized force is
//   Q_i = −γ m ∫ b_i Σ_j b_j q̇_j ds = −γ (M q̇)_i,
// i.e. mass-proportional damping (the "high viscosity" of the intestine model, [Lenoir talk 2008]).
// It only removes energy: dE/dt = −γ q̇ᵀ M q̇ <= 0. A body's internal DOFs are damped the same
// way through their own mass operator (a frame's spin: τ = −γ J ω), so that everything the body
// moves settles at the rate γ.
#pragma once

#include <memory>

#include "filum/core/force_field.hpp"
#include "filum/core/params.hpp"

namespace filum::mechanics {

class ViscousDamping final : public ForceField {
 public:
  /// coefficient γ (1/s) >= 0: a free body's velocity decays as e^{−γ t}.
  explicit ViscousDamping(double coefficient) : coefficient_(coefficient) {}
  static std::unique_ptr<ViscousDamping> fromParams(const Params& p) {
    return std::make_unique<ViscousDamping>(p.nonNegative({"coefficient", "1/s"}, 0.0));
  }

  std::string typeName() const override { return "ViscousDamping"; }
  void addForce(const SceneState& s, VecX& B) const override;
  /// ∂Q/∂q = 0, ∂Q/∂q̇ = −γ M ⊗ I₃.
  void addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const override;
  bool jacobianIsConstant() const override { return true; }
  bool hasJacobian() const override { return true; }

 private:
  void init(const Scene& scene) override;

  double coefficient_;
  mutable Points mv_;  // workspace M q̇
  mutable VecX internal_mv_;  // workspace M ω of the internal DOFs
};

}  // namespace filum::mechanics
