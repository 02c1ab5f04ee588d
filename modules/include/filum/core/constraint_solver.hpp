// ConstraintSolver: turns the unconstrained (tendency) accelerations A_t = M⁻¹B into
// accelerations that satisfy L A = E (paper §4; talk 002 "acceleration decomposition") — and,
// for the inequality rows of contacts (ConstraintRows::Kind), Signorini's and Coulomb's laws.
// One solver serves every integrator: explicit stages pass the mass matrix as A, implicit steps
// their step matrix.
#pragma once

#include "filum/core/block_inverse.hpp"
#include "filum/core/component.hpp"
#include "filum/core/constraint_rows.hpp"
#include "filum/core/scene_state.hpp"

namespace filum {

class Scene;

class ConstraintSolver : public Component {
 public:
  /// Solves  A a = b,  L a = E  for a, given a_t = A⁻¹ b in `a` on entry (the constrained
  /// result on exit). `inverse` applies A⁻¹ body by body (the mass matrix for explicit steps).
  virtual void solve(const Scene& scene, const ConstraintRows& rows, const BlockInverse& inverse, VecX& a) = 0;
  /// λ of the last solve, one per row (N for a point row; contact rows report their force).
  virtual Eigen::Ref<const VecX> multipliers() const = 0;
};

}  // namespace filum
