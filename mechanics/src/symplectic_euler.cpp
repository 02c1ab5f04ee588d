#include "filum/mechanics/symplectic_euler.hpp"

#include "filum/core/scene.hpp"

namespace filum::mechanics {

void SymplecticEuler::step(Scene& scene, SceneState& s, double dt) {
  scene.computeAcceleration(s, a_);
  s.v += dt * a_;
  scene.integratePositions(s.q, s.v, dt, s.q);  // q ⊕ dt v_{n+1}
  s.time += dt;
}

}  // namespace filum::mechanics
