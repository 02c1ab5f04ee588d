#include "uniform_acceleration.hpp"

#include "filum/core/mechanical_state.hpp"

namespace custom_app {

void UniformAcceleration::init(const filum::Scene&) {
  ones_a_ = acceleration_.transpose().replicate(body().pointCount(), 1);
  q_.resize(body().pointCount(), 3);
}

void UniformAcceleration::addForce(const filum::SceneState&, filum::VecX& B) const {
  // Q = M (1 ⊗ a)
  body().multiplyMass(ones_a_, q_);
  body().block(B) += q_;
}

}  // namespace custom_app
