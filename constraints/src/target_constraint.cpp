#include "filum/constraints/target_constraint.hpp"

#include <sstream>

#include "filum/core/scene_error.hpp"

namespace filum::constraints {

void steerTarget(Constraint& constraint, const SceneState& now, const Vec3& position, const Vec3& velocity) {
  auto* held = dynamic_cast<TargetConstraint*>(&constraint);
  if (!held) throw SceneError(constraint.describe(), "a point constraint with a target to steer", constraint.typeName());
  // A released constraint has no rows: its target would move while its point lies elsewhere.
  if (constraint.releasedAt(now) || !constraint.active()) {
    std::ostringstream found;
    found << "a constraint that holds nothing since ";
    if (!constraint.active() && !constraint.releasedAt(now))
      found << "it was switched off";
    else if (constraint.releaseTime() && now.time >= *constraint.releaseTime())
      found << "its \"release_at\" (" << *constraint.releaseTime() << " s; now t = " << now.time << " s)";
    else
      found << "it let its point go (t = " << now.time << " s: slid out or cut)";
    throw SceneError(constraint.describe(), "a point constraint that holds its point", found.str());
  }
  if (!held->target().steer(position, velocity, now.time))
    throw SceneError(constraint.describe(), "a target that can be steered",
                     "a target that is a point of another body (it moves with that body)");
}

}  // namespace filum::constraints
