#include "filum/mechanics/viscous_damping.hpp"

#include "filum/core/mechanical_state.hpp"

namespace filum::mechanics {

void ViscousDamping::init(const Scene&) { mv_.resize(body().pointCount(), 3); }

void ViscousDamping::addForce(const SceneState& s, VecX& B) const {
  // Q = −γ M q̇
  body().multiplyMass(body().block(s.v), mv_);
  body().block(B) -= coefficient_ * mv_;
}

}  // namespace filum::mechanics
