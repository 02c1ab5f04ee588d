// The static equilibrium of a rod held at node 0 (its three coordinates are not unknowns), for
// tests: Newton's method on the generalized forces the scene sums (the bodies' gravity and every
// force field's addForce; PointLoad and gravity scaled as the load), with a central-difference
// Jacobian over the velocity-space increments (points moved, frames turned by R ← R exp(δ)
// through Scene::integratePositions), the load applied in steps from the initial state. The
// Jacobian only steers Newton; the residual is the code's own force, converged to round-off.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "filum/core/scene.hpp"

namespace filum::test {

/// The rod of the rod tests: a polymer catheter-like rod, L = 0.2 m, r = 1 mm, ρ = 1100 kg/m³
/// (A = π r², I = π r⁴/4), and E set from the load parameter Γ = ρ A g L³ / (E I).
namespace rod {
constexpr double kLength = 0.2, kRadius = 1e-3, kDensity = 1100.0, kGravity = 9.81;
constexpr double kArea = std::numbers::pi * kRadius * kRadius, kSecond = kArea * kRadius * kRadius / 4.0;
inline double modulusFor(double gamma) { return kDensity * kArea * kGravity * std::pow(kLength, 3) / (gamma * kSecond); }
}  // namespace rod

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
    VecX F = reduced(s, load);
    const double imbalance = F.cwiseAbs().maxCoeff();  // what this load step has to balance
    double residual = imbalance;
    bool converged = imbalance == 0.0;
    for (int iteration = 0; iteration < 60 && !converged; ++iteration) {
      // J = ∂F/∂w by central differences, h = 1e-8 (m or rad): truncation h² |F'''| and round-off
      // ε |F| / h both far below what Newton needs (it only steers; the residual is exact).
      MatX J(free, free);
      const double h = 1e-8;
      for (int k = 0; k < free; ++k) {
        VecX e = VecX::Zero(free);
        e[k] = 1.0;
        J.col(k) = (reduced(moved(s, e, h), load) - reduced(moved(s, e, -h), load)) / (2.0 * h);
      }
      const VecX dw = J.partialPivLu().solve(-F);
      // The residual's round-off floor: positions known to ε |x| move F by ε |x| |∂F/∂w|.
      const double floor = std::numeric_limits<double>::epsilon() * s.q.head(3 * scene.dofPointCount()).cwiseAbs().maxCoeff() *
                           J.cwiseAbs().maxCoeff();
      // Full Newton steps, as finite-element codes take them on geometrically nonlinear beams
      // (Crisfield, Non-linear finite element analysis of solids and structures, §9): the first
      // step of a load increment stretches the turned segments by l θ²/2, which raises |F| and
      // the energy (E A ≫ the loads) and which the next step removes; a line search on either
      // would stall there.
      s = moved(s, dw, 1.0);
      F = reduced(s, load);
      const double next = F.cwiseAbs().maxCoeff();
      // Stop on the true residual: no longer contracting (Newton, quadratic near the solution,
      // has reached the residual's round-off floor), and there — below 1e-8 of the step's
      // imbalance or within 10 times the floor, whichever is larger (the floor, ~1e-13 N for
      // these rods, can exceed 1e-8 of a small load's imbalance).
      converged = next == 0.0 || (next <= std::max(1e-8 * imbalance, 10.0 * floor) && next > 0.5 * residual);
      residual = next;
    }
    EXPECT_TRUE(converged) << "Newton stalled at load step " << step << ", residual " << residual << " of "
                           << imbalance;
  }
  return s;
}

inline SceneState equilibrium(const Scene& scene, int increments) { return equilibrium(scene, increments, scene.state()); }

}  // namespace filum::test
