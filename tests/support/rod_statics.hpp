// The static equilibrium of a rod held at node 0 (its three coordinates are not unknowns), for
// tests: Newton's method on the generalized forces the scene sums (the bodies' gravity and every
// force field's addForce; PointLoad and gravity scaled as the load), with a central-difference
// Jacobian over the velocity-space increments (points moved, frames turned by R ← R exp(δ)
// through Scene::integratePositions), the load applied in steps from the initial state. The
// Jacobian only steers Newton; the residual is the code's own force, converged to round-off.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "filum/core/scene.hpp"

namespace filum::test {

/// The generalized forces at s (points and frames, velocity layout), the loads scaled by load.
inline VecX rodForces(const Scene& scene, const SceneState& s, double load) {
  VecX elastic = VecX::Zero(scene.velocitySize()), loads = VecX::Zero(scene.velocitySize());
  for (const MechanicalState* body : scene.bodies()) body->addGravity(scene.settings().gravity, body->block(loads));
  for (const ForceField* field : scene.forceFields()) field->addForce(s, field->typeName() == "PointLoad" ? loads : elastic);
  return elastic + load * loads;
}

/// The clamped rod's equilibrium under its loads, reached in `increments` load steps by Newton
/// from `start` (node 0 held: its three coordinates are not unknowns; forces at start.time, so
/// that a path in time can be followed by calls at successive times). Fails the test if Newton
/// stalls.
inline SceneState equilibrium(const Scene& scene, int increments, const SceneState& start) {
  SceneState s = start;
  const int n = scene.velocitySize(), free = n - 3;
  const auto reduced = [&](const SceneState& at, double load) { return VecX(rodForces(scene, at, load).tail(free)); };
  const auto moved = [&](const SceneState& at, const VecX& w_free, double h) {
    VecX w = VecX::Zero(n);
    w.tail(free) = w_free;
    SceneState out = at;
    scene.integratePositions(at.q, w, h, out.q);
    return out;
  };
  for (int step = 1; step <= increments; ++step) {
    const double load = double(step) / increments;
    double residual = reduced(s, load).cwiseAbs().maxCoeff();
    int iteration = 0;
    for (; iteration < 60; ++iteration) {
      // J = ∂F/∂w by central differences, h = 1e-8 (m or rad): truncation h² |F'''| and round-off
      // ε |F| / h both far below what Newton needs (it only steers; the residual is exact).
      MatX J(free, free);
      const double h = 1e-8;
      for (int k = 0; k < free; ++k) {
        VecX e = VecX::Zero(free);
        e[k] = 1.0;
        J.col(k) = (reduced(moved(s, e, h), load) - reduced(moved(s, e, -h), load)) / (2.0 * h);
      }
      const VecX F = reduced(s, load);
      const VecX dw = J.partialPivLu().solve(-F);
      // Full Newton steps, as finite-element codes take them on geometrically nonlinear beams
      // (Crisfield, Non-linear finite element analysis of solids and structures, §9): the first
      // step of a load increment stretches the turned segments by l θ²/2, which raises |F| and
      // the energy (E A ≫ the loads) and which the next step removes; a line search on either
      // would stall there.
      s = moved(s, dw, 1.0);
      residual = reduced(s, load).cwiseAbs().maxCoeff();
      // Converged when the update is at the round-off of positions (1e-13 of the rod's length)
      // and of angles (1e-13 rad).
      if (dw.cwiseAbs().maxCoeff() < 1e-13) break;
    }
    EXPECT_LT(iteration, 60) << "Newton stalled at load step " << step << ", residual " << residual;
  }
  return s;
}

inline SceneState equilibrium(const Scene& scene, int increments) { return equilibrium(scene, increments, scene.state()); }

}  // namespace filum::test
