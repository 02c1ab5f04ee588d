// ForceField: a term of the right-hand side B of M A = B (paper eq. 2–3): generalized forces
// Q_i = −∂E/∂q_i of an energy, or dissipative forces Q(q, q̇).
//
// Implicit integrators also need the force Jacobian: K = ∂Q/∂q (the stiffness, −∇²E for an
// energy) and D = ∂Q/∂q̇ (the damping). Fields provide them analytically through addJacobian;
// finite differences are for tests only (tests/support/finite_difference.hpp).
#pragma once

#include "filum/core/body_component.hpp"
#include "filum/core/jacobian_accumulator.hpp"
#include "filum/core/scene_state.hpp"

namespace filum {

class ForceField : public BodyComponent {
 public:
  /// Stage 2 of a (sub-)step of length h from state s (Scene::advance, before the integrator):
  /// a field that keeps something for the step (a lagged stiffness) starts afresh.
  virtual void beginStep(const SceneState& /*s*/, double /*h*/) {}
  /// B += generalized force of this field on its body at state s. B is the global 3N vector.
  virtual void addForce(const SceneState& s, VecX& B) const = 0;

  /// Potential energy stored by this field (J); 0 for dissipative fields.
  virtual double potentialEnergy(const SceneState& /*s*/) const { return 0.0; }

  /// Adds k_factor·K + d_factor·D at state s, K = ∂Q/∂q (N/m), D = ∂Q/∂q̇ (N·s/m), into `out`
  /// over the scene's global points (offset() + i), block by block. Implicit steps pass
  /// k_factor = −κh², d_factor = −θh to build M − θh D − κh² K. Must not allocate.
  /// Only called when hasJacobian().
  virtual void addJacobian(const SceneState& /*s*/, double /*k_factor*/, double /*d_factor*/,
                           JacobianAccumulator& /*out*/) const {}
  /// True when addJacobian is implemented; the scene refuses fields without it when the
  /// integrator needs Jacobians (Integrator::needsJacobians).
  virtual bool hasJacobian() const { return false; }
  /// True when K and D do not depend on the state (parametric bending, viscous damping): the
  /// step matrix then adds them once per step size into its constant part, not at every step.
  virtual bool jacobianIsConstant() const { return false; }

  /// Where the material this field models tears at state s: the abscissa of its largest tension
  /// and that tension (N), when it exceeds the material's strength (a stretching field with a
  /// break force); false otherwise. Scene::step cuts the body there before the next step.
  virtual bool tearsAt(const SceneState& /*s*/, double& /*abscissa*/, double& /*tension*/) const { return false; }
};

}  // namespace filum
