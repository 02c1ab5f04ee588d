// Implicit midpoint rule, solved by Newton iterations on the analytic force Jacobian
// (ImplicitStepSolver with θ = ½, κ = ¼):
//   v_{n+1} = v_n + h a,   q_{n+1} = q_n + h (v_n + v_{n+1})/2,
//   M a = Q((q_n + q_{n+1})/2, (v_n + v_{n+1})/2, t_n + h/2) + Lᵀλ.
// Second order, A-stable and symplectic: it conserves quadratic energies exactly (no numerical
// damping, unlike backward Euler) and needs no history, so the state stays one copyable value
// (BDF2 would need the previous step). Stiff modes are not damped (|R(∞)| = 1): pair it with
// RayleighDamping when the high modes matter. Chosen over BDF2 for these two reasons.
#pragma once

#include <memory>

#include "filum/core/integrator.hpp"
#include "filum/mechanics/implicit_step_solver.hpp"

namespace filum::mechanics {

class ImplicitMidpoint final : public Integrator {
 public:
  explicit ImplicitMidpoint(NewtonSettings settings = {}) : solver_(settings) {}
  /// "newton_iterations", "newton_tolerance", "linear_solver" (NewtonSettings).
  static std::unique_ptr<ImplicitMidpoint> fromParams(const Params& p) {
    return std::make_unique<ImplicitMidpoint>(NewtonSettings::fromParams(p));
  }
  std::string typeName() const override { return "ImplicitMidpoint"; }
  void step(Scene& scene, SceneState& s, double dt) override;
  int order() const override { return 2; }
  bool needsJacobians() const override { return true; }

  const ImplicitStepSolver& solver() const { return solver_; }

 private:
  ImplicitStepSolver solver_;
};

}  // namespace filum::mechanics
