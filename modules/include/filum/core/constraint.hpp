// Constraint: a bilateral constraint g(q, t) = 0 solved by Lagrange multipliers (paper §4).
// Each constraint contributes rows of L A = E where E carries the Baumgarte stabilization
// g̈ + 2ω ġ + ω² g = 0 (critically damped), so that drift is pulled back to zero.
#pragma once

#include "filum/core/body_component.hpp"
#include "filum/core/constraint_rows.hpp"
#include "filum/core/scene_state.hpp"

namespace filum {

class Constraint : public BodyComponent {
 public:
  /// Number of scalar rows (3 for a fixed point).
  virtual int rowCount() const = 0;

  /// Appends this constraint's rows of L A = E at state s to rows.
  virtual void buildRows(const SceneState& s, ConstraintRows& rows) const = 0;

  /// Position-level violation g(q, t) (m), rowCount() entries, written at g[first..].
  virtual void violation(const SceneState& s, VecX& g, int first) const = 0;

  /// A released constraint (a cut) contributes no rows. Releasing refactors nothing.
  bool active() const { return active_; }
  void setActive(bool active) { active_ = active; }

 private:
  bool active_ = true;
};

}  // namespace filum
