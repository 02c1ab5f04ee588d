#include "filum/core/mechanical_state.hpp"

namespace filum {

double MechanicalState::kineticEnergy(ConstPointsRef v) const {
  // K = ½ Σ_α (v^α)ᵀ M v^α (paper §3: M is the same block for x, y and z).
  Points mv(v.rows(), 3);
  multiplyMass(v, mv);
  return 0.5 * v.cwiseProduct(mv).sum();
}

void MechanicalState::addMassMatrix(double factor, JacobianAccumulator& out) const {
  // Generic fallback: column j of M is M e_j; M ⊗ I₃ puts M_ij on every axis (paper eq. 3).
  const int n = pointCount();
  Points unit = Points::Zero(n, 3), column(n, 3);
  for (int j = 0; j < n; ++j) {
    unit(j, 0) = 1.0;
    multiplyMass(unit, column);
    unit(j, 0) = 0.0;
    for (int i = 0; i < n; ++i)
      if (column(i, 0) != 0.0)
        out.addIsotropic(offset_ + i, offset_ + j, factor * column(i, 0));
  }
}

}  // namespace filum
