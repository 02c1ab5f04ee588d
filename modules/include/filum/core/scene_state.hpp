// SceneState: everything that changes during a step, in one copyable value (DESIGN.md
// "Model and state"). Copying it gives save/restore, rollback on divergence, determinism
// checks and the RK4 stages.
//
// Layout of q and v (and of the accelerations a = f(q, v, t)):
//   [ x0 y0 z0 x1 y1 z1 ... (3N point coordinates of every body, m, m/s, m/s²)
//   | e0 e1 ... (E extra scalar DOFs owned by constraints, e.g. a sliding point's abscissa
//     s(t), ṡ(t), s̈(t) — Scene::extraDofCount(), Constraint::extraIndex()) ].
// Extra DOFs sit in the same vectors on purpose: an integrator that advances q, v and a as
// whole vectors (RK4, symplectic Euler) advances them too, with the same order of accuracy,
// and copying the state copies them. E = 0 unless the scene has such constraints.
#pragma once

#include "filum/core/types.hpp"

namespace filum {

struct SceneState {
  double time = 0.0;  // simulated time (s), steps × dt: no running-sum round-off
  long steps = 0;     // steps taken since t = 0
  VecX q;             // positions: 3N point coordinates x0 y0 z0 x1 ..., then E extra DOFs
  VecX v;             // velocities, same layout (m/s for points)

  bool allFinite() const { return std::isfinite(time) && q.allFinite() && v.allFinite(); }
};

}  // namespace filum
