#include "filum/mechanics/runge_kutta4.hpp"

#include "filum/core/scene.hpp"

namespace filum::mechanics {

void RungeKutta4::step(Scene& scene, SceneState& s, double dt) {
  // k1 = f(y_n), k2 = f(y_n + dt/2 k1), k3 = f(y_n + dt/2 k2), k4 = f(y_n + dt k3),
  // y_{n+1} = y_n + dt/6 (k1 + 2 k2 + 2 k3 + k4), with k = (v, a) for y = (q, v). Positions move
  // by q ⊕ h w (Scene::integratePositions): q + h w for points, the body's own update for internal
  // DOFs (a rotation turned by the stages' weighted angular velocity: the first Magnus term is
  // matched to O(dt⁵), the commutator term O(dt³) is not, so orientations are second order;
  // velocities stay fourth order only while the forces do not depend on orientations, as for a
  // free top — with elastic torques and shear, as in a FramedChain, the scheme is second order).
  const double h = 0.5 * dt;
  scene.computeAcceleration(s, a1_);

  stage_.time = s.time + h;
  scene.integratePositions(s.q, s.v, h, stage_.q);
  v2_ = s.v + h * a1_;
  stage_.v = v2_;
  scene.computeAcceleration(stage_, a2_);

  scene.integratePositions(s.q, v2_, h, stage_.q);
  v3_ = s.v + h * a2_;
  stage_.v = v3_;
  scene.computeAcceleration(stage_, a3_);

  stage_.time = s.time + dt;
  scene.integratePositions(s.q, v3_, dt, stage_.q);
  v4_ = s.v + dt * a3_;
  stage_.v = v4_;
  scene.computeAcceleration(stage_, a4_);

  velocity_ = s.v + 2.0 * v2_ + 2.0 * v3_ + v4_;
  scene.integratePositions(s.q, velocity_, dt / 6.0, s.q);
  s.v += (dt / 6.0) * (a1_ + 2.0 * a2_ + 2.0 * a3_ + a4_);
  s.time += dt;
}

}  // namespace filum::mechanics
