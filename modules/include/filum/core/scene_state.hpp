// SceneState: everything that changes during a step, in one copyable value (DESIGN.md
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

#include "filum/core/types.hpp"

namespace filum {

struct SceneState {
  double time = 0.0;  // simulated time (s), steps × dt: no running-sum round-off
  long steps = 0;     // steps taken since t = 0
  VecX q;             // positions: 3N point coordinates x0 y0 z0 x1 ..., E extra DOFs, internal DOFs
  VecX v;             // velocities: the same up to the internal DOFs (m/s for points)

  bool allFinite() const { return std::isfinite(time) && q.allFinite() && v.allFinite(); }
};

}  // namespace filum
