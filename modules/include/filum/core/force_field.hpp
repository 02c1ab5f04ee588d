// ForceField: a term of the right-hand side B of M A = B (paper eq. 2–3): generalized forces
// Q_i = −∂E/∂q_i of an energy, or dissipative forces.
#pragma once

#include "filum/core/body_component.hpp"
#include "filum/core/scene_state.hpp"

namespace filum {

class ForceField : public BodyComponent {
 public:
  /// B += generalized force of this field on its body at state s. B is the global 3N vector.
  virtual void addForce(const SceneState& s, VecX& B) const = 0;

  /// Potential energy stored by this field (J); 0 for dissipative fields.
  virtual double potentialEnergy(const SceneState& /*s*/) const { return 0.0; }
};

}  // namespace filum
