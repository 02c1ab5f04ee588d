// Semi-implicit (symplectic) Euler:  v_{n+1} = v_n + dt A(q_n, v_n, t_n),  q_{n+1} = q_n + dt v_{n+1}.
// First order, symplectic for conservative forces: energy error stays bounded instead of drifting.
#pragma once

#include <memory>

#include "filum/core/integrator.hpp"
#include "filum/core/params.hpp"

namespace filum::mechanics {

class SymplecticEuler final : public Integrator {
 public:
  static std::unique_ptr<SymplecticEuler> fromParams(const Params&) { return std::make_unique<SymplecticEuler>(); }
  std::string typeName() const override { return "SymplecticEuler"; }
  void step(Scene& scene, SceneState& s, double dt) override;
  int order() const override { return 1; }

 private:
  VecX a_;  // workspace
};

}  // namespace filum::mechanics
