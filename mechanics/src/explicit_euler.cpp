#include "filum/mechanics/explicit_euler.hpp"

#include "filum/core/scene.hpp"

namespace filum::mechanics {

void ExplicitEuler::step(Scene& scene, SceneState& s, double dt) {
  scene.computeAcceleration(s, a_);
  scene.integratePositions(s.q, s.v, dt, s.q);  // q ⊕ dt v with v_n, before the velocity update
  s.v += dt * a_;
  s.time += dt;
}

}  // namespace filum::mechanics
