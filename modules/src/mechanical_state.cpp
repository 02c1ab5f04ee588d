#include "filum/core/mechanical_state.hpp"

namespace filum {

double MechanicalState::kineticEnergy(ConstPointsRef v) const {
  // K = ½ Σ_α (v^α)ᵀ M v^α (paper §3: M is the same block for x, y and z).
  Points mv(v.rows(), 3);
  multiplyMass(v, mv);
  return 0.5 * v.cwiseProduct(mv).sum();
}

}  // namespace filum
