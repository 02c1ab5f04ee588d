// StiffnessDerivative: an elastic force field that can also differentiate its stiffness,
//   ∂(K(q) w)/∂q   for a fixed vector w   (K = ∂Q/∂q = −∇²E: third derivatives of the energy).
// Stiffness-proportional damping Q = β K(q) q̇ (RayleighDamping) needs it for the exact
// position Jacobian ∂Q/∂q = β ∂(K(q) q̇)/∂q; without it Newton on an implicit step converges
// only linearly (measured: ~5× per iteration instead of quadratically for a stiff suture).
// A mechanics-level interface (not in core::ForceField): only damping models built on a
// stiffness use it.
#pragma once

#include "filum/core/scene_state.hpp"
#include "filum/core/types.hpp"

namespace filum::mechanics {

class StiffnessDerivative {
 public:
  virtual ~StiffnessDerivative() = default;
  /// Appends factor · ∂(K(q) w)/∂q at state s as triplets over global 3N coordinates; w is a
  /// global 3N vector (e.g. the velocities).
  virtual void addStiffnessDerivative(const SceneState& s, const VecX& w, double factor, JacobianAccumulator& out) const = 0;
};

}  // namespace filum::mechanics
