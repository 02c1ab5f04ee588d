// SceneState: everything that changes during a step, in one copyable value (DESIGN.md
// "Model and state"). Copying it gives save/restore, rollback on divergence, determinism
// checks and the RK4 stages.
#pragma once

#include "filum/core/types.hpp"

namespace filum {

struct SceneState {
  double time = 0.0;  // simulated time (s), steps × dt: no running-sum round-off
  long steps = 0;     // steps taken since t = 0
  VecX q;             // positions of every point DOF of every body, x0 y0 z0 x1 ... (3N, m)
  VecX v;             // velocities (3N, m/s)

  bool allFinite() const { return std::isfinite(time) && q.allFinite() && v.allFinite(); }
};

}  // namespace filum
