// Constraint: a bilateral constraint g(q, t) = 0 solved by Lagrange multipliers (paper §4).
// Each constraint contributes rows of L A = E where E carries the Baumgarte stabilization
// g̈ + 2ω ġ + ω² g = 0 (critically damped), so that drift is pulled back to zero.
//
// Besides its rows a constraint may own scalar degrees of freedom of its own ("extra" DOFs,
// laid out after the points in SceneState::q and v, see scene_state.hpp): a sliding point's
// abscissa s(t) ([Lenoir talk 2008], suturing), whose acceleration follows from the point accelerations
// once the multipliers are known (extraAcceleration). It may also apply known forces
// (addForce: friction along a sliding point's tangent), and it may be released at a scheduled
// time ("release_at" in the scene file) or when its own state says so (a thread that slid out
// of its hole) — a cut that removes rows without refactoring anything.
#pragma once

#include <optional>

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

  /// Number of entries of violation(); rowCount() unless the rows constrain a projection of
  /// a larger gap (a sliding point has 2 rows but reports its whole 3D gap P(s) − P0).
  virtual int violationCount() const { return rowCount(); }
  /// Position-level violation g(q, t) (m), violationCount() entries, written at g[first..].
  virtual void violation(const SceneState& s, VecX& g, int first) const = 0;

  /// Generalized forces this constraint applies besides its multipliers (e.g. friction along
  /// a sliding point's tangent), added to B before the tendency solve: B += Q (3N, N).
  virtual void addForce(const SceneState& /*s*/, VecX& /*B*/) const {}

  /// Where a point constraint holds its point at state s (its fixed, scripted or attached
  /// target), for whoever shows or follows it (a sphere drawn at the target); nullopt for
  /// constraints without a target point.
  virtual std::optional<Vec3> targetPoint(const SceneState& /*s*/) const { return std::nullopt; }
  /// Whether targetPoint gives a point (a point constraint), known once the scene is built.
  virtual bool hasTargetPoint() const { return false; }

  // Extra scalar DOFs owned by this constraint (SceneState layout: after the 3N point
  // coordinates, at extraIndex() .. extraIndex() + extraDofCount() − 1 of q, v and a).

  /// How many extra DOFs this constraint owns (fixed once bound).
  virtual int extraDofCount() const { return 0; }
  /// Their initial positions (velocities start at zero), written at q[extraIndex()...].
  virtual void initialExtra(VecX& /*q*/) const {}
  /// Their accelerations at state s, written at a[extraIndex()...], once a holds the
  /// constrained point accelerations (after the multiplier solve). Called for released
  /// constraints too (which should then write zeros).
  virtual void extraAcceleration(const SceneState& /*s*/, VecX& /*a*/) const {}
  int extraIndex() const { return extra_index_; }
  void setExtraIndex(int index) { extra_index_ = index; }

  /// A released constraint (a cut) contributes no rows. Releasing refactors nothing: the
  /// bodies' mass matrices stay factored and the other rows are built as before.
  /// active() = enabled by the user (setActive) and not released by its schedule.
  bool active() const { return enabled_ && !released_; }
  void setActive(bool active) { enabled_ = active; }

  /// Scheduled release time (s), "release_at" in the scene file.
  const std::optional<double>& releaseTime() const { return release_time_; }
  void setReleaseTime(std::optional<double> t) { release_time_ = t; }
  /// Whether the constraint is released at state s: by default once s.time reaches the
  /// scheduled release time. A function of the state, so that restoring a state before the
  /// release restores the constraint too (save/restore and rollback stay exact).
  virtual bool releasedAt(const SceneState& s) const { return release_time_ && s.time >= *release_time_; }
  /// Called by the scene at the start of every step (and when a state is set).
  void updateRelease(const SceneState& s) { released_ = releasedAt(s); }

 private:
  bool enabled_ = true;
  bool released_ = false;
  std::optional<double> release_time_;
  int extra_index_ = 0;
};

}  // namespace filum
