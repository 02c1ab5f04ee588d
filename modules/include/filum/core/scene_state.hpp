// SceneState: everything that changes during a step, in one copyable value (docs/architecture.md,
// "Model and state"). Copying it gives save/restore, rollback on divergence, determinism
// checks and the RK4 stages.
//
// Layout of q and v (and of the accelerations a = f(q, v, t) and forces, laid out as v):
//   [ x0 y0 z0 x1 y1 z1 ... (3N point coordinates of every body, m, m/s, m/s²)
//   | e0 e1 ... (E extra scalar DOFs owned by constraints, e.g. a sliding point's abscissa
//     s(t), ṡ(t), s̈(t) — Scene::extraDofCount(), Constraint::extraIndex())
//   | the bodies' internal DOFs, body by body (MechanicalState::internalPositionCount() values in
//     q, internalVelocityCount() in v: a rotation's unit quaternion in q, its angular velocity
//     in v) ].
// Points and extra DOFs have the same index in q and v; only the internal tail may differ in
// length (Scene::positionSize(), velocitySize()). Extra DOFs sit in the same vectors on purpose:
// an integrator that advances q, v and a as whole vectors advances them too, with the same order
// of accuracy, and copying the state copies them. Positions advance from velocities through
// Scene::integratePositions (q ⊕ h v: q + h v for points and extras, the body's own update for its
// internal DOFs). E = 0 unless the scene has such constraints; no internal tail unless a body has
// internal DOFs.
#pragma once

#include <algorithm>
#include <vector>

#include "filum/core/growing_vector.hpp"
#include "filum/core/types.hpp"

namespace filum {

/// What the next step reads beyond q and v: the linearization point of a step matrix an implicit
/// integrator keeps factored and when it reuses it, the constraint solver's last multipliers (its
/// warm start) and the collision pipeline's last contact forces (the next detection's warm start).
/// The step leaves it in the state (Scene::endStep) and Scene::setState hands it back, so that a
/// restored state reruns bit for bit what followed it the first time. The components fill and
/// read it (Integrator, ConstraintSolver, CollisionPipeline: saveMemory, restoreMemory); empty
/// (the default) means a fresh start, as after Scene::init.
struct StepMemory {
  StepMemory() = default;
  StepMemory(const StepMemory&) = default;
  /// Copies into storage that grows geometrically: a state copied every step (Scene's last good
  /// state) allocates only when the contact count reaches a new power of two, not at every new
  /// maximum.
  StepMemory& operator=(const StepMemory& other);
  long layout_revision = -1;  // Scene::layoutRevision() when saved (-1: never saved, not checked)
  // Integrator: a kept factorization (an id unique in the process, so that restoring the matrix
  // the integrator holds costs nothing), its (h, θ, κ), the state it was assembled at, and the
  // reuse schedule.
  long matrix_id = 0;  // 0: none kept
  double matrix_key[3] = {0.0, 0.0, 0.0};
  double matrix_time = 0.0;
  VecX matrix_q, matrix_v;
  int reuse_skip = 0, reuse_backoff = 0;
  bool fresh_next = false;
  // Constraint solver: λ of its last call and the kinds of those rows.
  std::vector<double> multipliers;
  std::vector<int> row_kinds;
  // Collision pipeline: its last contacts with their forces, packed by the pipeline.
  std::vector<double> contacts;
  // Scene: the halving depth the next step starts its sub-steps at (Scene::advanceStep).
  int substep_depth = 0;
};

inline StepMemory& StepMemory::operator=(const StepMemory& other) {
  if (this == &other) return *this;
  layout_revision = other.layout_revision;
  matrix_id = other.matrix_id;
  for (int k = 0; k < 3; ++k) matrix_key[k] = other.matrix_key[k];
  matrix_time = other.matrix_time;
  matrix_q = other.matrix_q;  // the layout's size: resized only when the layout changes
  matrix_v = other.matrix_v;
  reuse_skip = other.reuse_skip;
  reuse_backoff = other.reuse_backoff;
  fresh_next = other.fresh_next;
  assignGrowing(multipliers, other.multipliers);
  assignGrowing(row_kinds, other.row_kinds);
  assignGrowing(contacts, other.contacts);
  substep_depth = other.substep_depth;
  return *this;
}

struct SceneState {
  double time = 0.0;  // simulated time (s), steps × dt: no running-sum round-off
  long steps = 0;     // steps taken since t = 0
  VecX q;             // positions: 3N point coordinates x0 y0 z0 x1 ..., E extra DOFs, internal DOFs
  VecX v;             // velocities: the same up to the internal DOFs (m/s for points)
  StepMemory memory;  // what the next step reads beyond q and v (above)

  bool allFinite() const { return std::isfinite(time) && q.allFinite() && v.allFinite(); }
};

}  // namespace filum
