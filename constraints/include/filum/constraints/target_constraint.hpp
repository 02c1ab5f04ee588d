// TargetConstraint: a constraint that holds a point of its body to a PointTarget (fixed point,
// point on axis, point on plane, clamp, sliding point). Applications reach the target through
// this interface, without naming the concrete constraint, to steer it between steps
// (PointTarget::steer: a tool moved by a script or a device; Python's Scene.steer).
#pragma once

#include "filum/constraints/point_target.hpp"
#include "filum/core/constraint.hpp"

namespace filum::constraints {

class TargetConstraint {
 public:
  virtual ~TargetConstraint() = default;
  virtual const PointTarget& target() const = 0;
  /// Changing the target changes what the constraint's rows hold from the next step on.
  virtual PointTarget& target() = 0;
};

/// Steers the target of `constraint` (a TargetConstraint) from state `now` on: X(t) = position +
/// velocity (t − now.time). Throws SceneError naming the constraint when it is not one that holds
/// its point to a target, when it holds nothing any more (released by its "release_at", by a cut,
/// or switched off) or when its target is a point of another body, which moves with that body.
void steerTarget(Constraint& constraint, const SceneState& now, const Vec3& position, const Vec3& velocity);

}  // namespace filum::constraints
