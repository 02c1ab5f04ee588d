// Implicit (backward) Euler, solved by Newton iterations on the analytic force Jacobian
// (ImplicitStepSolver with θ = κ = 1):
//   v_{n+1} = v_n + h a,   q_{n+1} = q_n + h v_{n+1},
//   M a = Q(q_{n+1}, v_{n+1}, t_{n+1}) + Lᵀλ.
// First order, L-stable: stiff modes (real suture stiffness, ω h ≫ 1) are damped instead of
// blowing up, and for a convex energy (a thread in tension) the total energy never increases:
// E_{n+1} − E_n <= −½ |v_{n+1} − v_n|²_M. The paper's implicit method (§3, [HMC01]).
#pragma once

#include <memory>

#include "filum/core/integrator.hpp"
#include "filum/mechanics/implicit_step_solver.hpp"

namespace filum::mechanics {

class ImplicitEuler final : public Integrator {
 public:
  explicit ImplicitEuler(NewtonSettings settings = {}) : solver_(settings) {}
  /// "newton_iterations", "newton_tolerance", "linear_solver" (NewtonSettings).
  static std::unique_ptr<ImplicitEuler> fromParams(const Params& p) {
    return std::make_unique<ImplicitEuler>(NewtonSettings::fromParams(p));
  }
  std::string typeName() const override { return "ImplicitEuler"; }
  void step(Scene& scene, SceneState& s, double dt) override;
  void saveMemory(StepMemory& memory) const override { solver_.saveMemory(memory); }
  void restoreMemory(const Scene& scene, const StepMemory& memory) override { solver_.restoreMemory(scene, memory); }
  int order() const override { return 1; }
  bool needsJacobians() const override { return true; }

  const ImplicitStepSolver& solver() const { return solver_; }

 private:
  ImplicitStepSolver solver_;
};

}  // namespace filum::mechanics
