// Explicit (forward) Euler:  q_{n+1} = q_n + dt v_n,  v_{n+1} = v_n + dt A(q_n, v_n, t_n).
// First order; unstable for every undamped oscillation (its amplification factor is
// |1 + i ω dt| > 1), kept as the baseline of the accuracy and stability benchmarks.
#pragma once

#include <memory>

#include "filum/core/integrator.hpp"
#include "filum/core/params.hpp"

namespace filum::mechanics {

class ExplicitEuler final : public Integrator {
 public:
  static std::unique_ptr<ExplicitEuler> fromParams(const Params&) { return std::make_unique<ExplicitEuler>(); }
  std::string typeName() const override { return "ExplicitEuler"; }
  void step(Scene& scene, SceneState& s, double dt) override;
  int order() const override { return 1; }

 private:
  VecX a_;  // workspace
};

}  // namespace filum::mechanics
