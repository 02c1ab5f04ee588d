#include "filum/mechanics/viscous_damping.hpp"

#include "filum/core/mechanical_state.hpp"

namespace filum::mechanics {

void ViscousDamping::init(const Scene&) {
  mv_.resize(body().pointCount(), 3);
  internal_mv_.resize(body().internalVelocityCount());
}

void ViscousDamping::addForce(const SceneState& s, VecX& B) const {
  // Q = −γ M q̇
  body().multiplyMass(body().block(s.v), mv_);
  body().block(B) -= coefficient_ * mv_;
  if (body().internalVelocityCount() > 0) {  // Q_int = −γ M_int v_int
    body().multiplyInternalMass(body().internalVelocities(s.v), internal_mv_);
    body().internalVelocities(B) -= coefficient_ * internal_mv_;
  }
}

void ViscousDamping::addJacobian(const SceneState&, double, double d_factor, JacobianAccumulator& out) const {
  if (d_factor == 0.0 || coefficient_ == 0.0) return;
  body().addMassMatrix(-coefficient_ * d_factor, out);
  if (body().internalVelocityCount() > 0) body().addInternalMassMatrix(-coefficient_ * d_factor, out);
}

}  // namespace filum::mechanics
