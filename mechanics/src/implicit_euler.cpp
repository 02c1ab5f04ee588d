#include "filum/mechanics/implicit_euler.hpp"

#include "filum/core/scene.hpp"

namespace filum::mechanics {

void ImplicitEuler::step(Scene& scene, SceneState& s, double dt) {
  // θ = κ = 1: forces at (q_n + h v_n + h² a, v_n + h a) = (q_{n+1}, v_{n+1});
  // v_{n+1} = v_n + h a, q_{n+1} = q_n + h v_{n+1} = q_n + h v_n + h² a. On failure the scene
  // rolls the step back.
  solver_.step(scene, s, dt, 1.0, 1.0, 1.0);
}

}  // namespace filum::mechanics
