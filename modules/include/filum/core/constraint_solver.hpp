// ConstraintSolver: turns the unconstrained (tendency) accelerations A_t = M⁻¹B into
// accelerations that satisfy L A = E (paper §4; talk 002 "acceleration decomposition").
#pragma once

#include "filum/core/component.hpp"
#include "filum/core/constraint_rows.hpp"
#include "filum/core/scene_state.hpp"

namespace filum {

class Scene;

class ConstraintSolver : public Component {
 public:
  /// a holds A_t on entry and the constrained A on exit.
  virtual void solve(const Scene& scene, const ConstraintRows& rows, VecX& a) = 0;
};

}  // namespace filum
