#include "filum/mechanics/viscous_damping.hpp"

#include "filum/core/mechanical_state.hpp"

namespace filum::mechanics {

void ViscousDamping::init(const Scene&) { mv_.resize(body().pointCount(), 3); }

void ViscousDamping::addForce(const SceneState& s, VecX& B) const {
  // Q = −γ M q̇
  body().multiplyMass(body().block(s.v), mv_);
  body().block(B) -= coefficient_ * mv_;
}

void ViscousDamping::addJacobian(const SceneState&, double, double d_factor, JacobianAccumulator& out) const {
  if (d_factor != 0.0 && coefficient_ != 0.0) body().addMassMatrix(-coefficient_ * d_factor, out);
}

}  // namespace filum::mechanics
