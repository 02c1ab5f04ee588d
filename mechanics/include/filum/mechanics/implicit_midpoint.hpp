// Implicit midpoint rule, solved by Newton iterations on the analytic force Jacobian
// (ImplicitStepSolver with θ = ½, κ = ¼):
//   v_{n+1} = v_n + h a,   q_{n+1} = q_n + h (v_n + v_{n+1})/2,
//   M a = Q((q_n + q_{n+1})/2, (v_n + v_{n+1})/2, t_n + h/2) + Lᵀλ.
// Second order, A-stable and symplectic: it conserves quadratic energies exactly (no numerical
// damping, unlike backward Euler) and needs no history, so the state stays one copyable value
// (BDF2 would need the previous step). Stiff modes are not damped (|R(∞)| = 1): pair it with
// RayleighDamping when the high modes matter. Chosen over BDF2 for these two reasons.
// Its linearized solve refactors the step matrix every step by default ("reuse_factorization":
// false, NewtonSettings::secondOrder): a chord step from a stale matrix, accepted at the
// estimate's 1e-3 of the step's motion, is below backward Euler's O(h) error but not below the
// midpoint rule's O(h²) one (the cantilever's error over one period at dt = 1e-4 s grew by up to
// 11 % with reuse, apps/bench/accuracy_pareto).
#pragma once

#include <memory>

#include "filum/core/integrator.hpp"
#include "filum/mechanics/implicit_step_solver.hpp"

namespace filum::mechanics {

class ImplicitMidpoint final : public Integrator {
 public:
  explicit ImplicitMidpoint(NewtonSettings settings = NewtonSettings::secondOrder()) : solver_(settings) {}
  /// "newton_iterations", "newton_tolerance", "linear_solver" (NewtonSettings).
  static std::unique_ptr<ImplicitMidpoint> fromParams(const Params& p) {
    return std::make_unique<ImplicitMidpoint>(NewtonSettings::fromParams(p, NewtonSettings::secondOrder()));
  }
  std::string typeName() const override { return "ImplicitMidpoint"; }
  void step(Scene& scene, SceneState& s, double dt) override;
  void saveMemory(StepMemory& memory) const override { solver_.saveMemory(memory); }
  void restoreMemory(const Scene& scene, const StepMemory& memory) override { solver_.restoreMemory(scene, memory); }
  int order() const override { return 2; }
  bool needsJacobians() const override { return true; }
  /// A rod's frames (internal DOFs): their shear modes (ω ~ 1e5–1e6 rad/s) are stiff, and the
  /// midpoint rule does not damp them (|R(∞)| = 1): apps/scenes/j_tip_catheter.json under it
  /// failed Newton at t = 0.15 s even with 1024 sub-steps (when halving stopped at depth 10).
  /// Backward Euler damps them.
  std::string internalDofsRefusal() const override {
    return "ImplicitEuler or an explicit integrator (the midpoint rule leaves a rod's stiff frame modes undamped)";
  }

  const ImplicitStepSolver& solver() const { return solver_; }

 private:
  ImplicitStepSolver solver_;
};

}  // namespace filum::mechanics
