// UniformAcceleration: the application's own force field, a body force that accelerates every
// material point of the curve by the same a (a steady wind tunnel, a centrifuge, a tilted table):
// force density f(s) = μ(s) a, whose generalized force is
//   Q_i = ∫ b_i(s) μ(s) a ds = Σ_j M_ij a      (the basis sums to 1 at every s),
// i.e. Q = M (1 ⊗ a). It is constant in q and q̇: zero Jacobian.
#pragma once

#include <memory>

#include "filum/core/force_field.hpp"
#include "filum/core/params.hpp"

namespace custom_app {

class UniformAcceleration final : public filum::ForceField {
 public:
  /// acceleration a (m/s²) given to every material point.
  explicit UniformAcceleration(const filum::Vec3& acceleration) : acceleration_(acceleration) {}
  /// Scene-file form: {"type": "UniformAcceleration", "acceleration": [ax, ay, az]}.
  static std::unique_ptr<UniformAcceleration> fromParams(const filum::Params& p) {
    return std::make_unique<UniformAcceleration>(p.vec3({"acceleration", "m/s²"}));
  }

  std::string typeName() const override { return "UniformAcceleration"; }
  void addForce(const filum::SceneState& s, filum::VecX& B) const override;
  /// K = D = 0: implicit integrators accept the field and add nothing to their matrix.
  bool hasJacobian() const override { return true; }
  bool jacobianIsConstant() const override { return true; }

 private:
  void init(const filum::Scene& scene) override;

  filum::Vec3 acceleration_;
  filum::Points ones_a_;      // 1 ⊗ a, one row per control point (set by init)
  mutable filum::Points q_;   // workspace M (1 ⊗ a): no allocation in a step
};

}  // namespace custom_app
