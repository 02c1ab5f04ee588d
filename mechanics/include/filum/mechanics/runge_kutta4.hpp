// Classical fourth-order Runge-Kutta on y = (q, v), y' = (v, A(q, v, t)) — the explicit
// integrator of the paper (§3) and of the intestine model ([Lenoir talk 2008]). Stage k evaluates the
// scene's accelerations at a stage state; the stage states reuse preallocated storage.
#pragma once

#include <memory>

#include "filum/core/integrator.hpp"
#include "filum/core/params.hpp"

namespace filum::mechanics {

class RungeKutta4 final : public Integrator {
 public:
  static std::unique_ptr<RungeKutta4> fromParams(const Params&) { return std::make_unique<RungeKutta4>(); }
  std::string typeName() const override { return "RungeKutta4"; }
  void step(Scene& scene, SceneState& s, double dt) override;
  int order() const override { return 4; }

 private:
  SceneState stage_;
  VecX a1_, a2_, a3_, a4_, v2_, v3_, v4_;
  VecX velocity_;  // v1 + 2 v2 + 2 v3 + v4
};

}  // namespace filum::mechanics
