#include "filum/mechanics/runge_kutta4.hpp"

#include "filum/core/scene.hpp"

namespace filum::mechanics {

void RungeKutta4::step(Scene& scene, SceneState& s, double dt) {
  // k1 = f(y_n), k2 = f(y_n + dt/2 k1), k3 = f(y_n + dt/2 k2), k4 = f(y_n + dt k3),
  // y_{n+1} = y_n + dt/6 (k1 + 2 k2 + 2 k3 + k4), with k = (v, a) for y = (q, v).
  const double h = 0.5 * dt;
  scene.computeAcceleration(s, a1_);

  stage_.time = s.time + h;
  stage_.q = s.q + h * s.v;
  v2_ = s.v + h * a1_;
  stage_.v = v2_;
  scene.computeAcceleration(stage_, a2_);

  stage_.q = s.q + h * v2_;
  v3_ = s.v + h * a2_;
  stage_.v = v3_;
  scene.computeAcceleration(stage_, a3_);

  stage_.time = s.time + dt;
  stage_.q = s.q + dt * v3_;
  v4_ = s.v + dt * a3_;
  stage_.v = v4_;
  scene.computeAcceleration(stage_, a4_);

  s.q += (dt / 6.0) * (s.v + 2.0 * v2_ + 2.0 * v3_ + v4_);
  s.v += (dt / 6.0) * (a1_ + 2.0 * a2_ + 2.0 * a3_ + a4_);
  s.time += dt;
}

}  // namespace filum::mechanics
