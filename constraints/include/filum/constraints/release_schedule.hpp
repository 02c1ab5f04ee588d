// Scheduled release of a constraint (a cut at a predefined time, [Lenoir talk 2008] "release appropriate
// constraints to cut"): "release_at": t (s, >= 0) in the scene file. From the first step that
// starts at or after t the constraint contributes no rows (Constraint::releasedAt); nothing is
// refactored. Read by every constraint of this library, so that only constraints accept it.
#pragma once

#include "filum/core/constraint.hpp"
#include "filum/core/params.hpp"

namespace filum::constraints {

/// Reads "release_at" (optional, >= 0) into c.
inline void readReleaseTime(const Params& p, Constraint& c) {
  if (p.has("release_at")) c.setReleaseTime(p.nonNegative({"release_at", "s"}, 0.0));
}

}  // namespace filum::constraints
