#include "filum/mechanics/implicit_midpoint.hpp"

#include "filum/core/scene.hpp"

namespace filum::mechanics {

void ImplicitMidpoint::step(Scene& scene, SceneState& s, double dt) {
  // θ = ½, κ = ¼: forces at ((q_n + q_{n+1})/2, (v_n + v_{n+1})/2) = (q_n + h/2 v_n + h²/4 a,
  // v_n + h/2 a); v_{n+1} = v_n + h a, q_{n+1} = q_n + h (v_n + v_{n+1})/2 = q_n + h v_n + h²/2 a.
  solver_.step(scene, s, dt, 0.5, 0.25, 0.5);
}

}  // namespace filum::mechanics
