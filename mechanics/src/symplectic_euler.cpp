#include "filum/mechanics/symplectic_euler.hpp"

#include "filum/core/scene.hpp"

namespace filum::mechanics {

void SymplecticEuler::step(Scene& scene, SceneState& s, double dt) {
  scene.computeAcceleration(s, a_);
  s.v += dt * a_;
  s.q += dt * s.v;
  s.time += dt;
}

}  // namespace filum::mechanics
