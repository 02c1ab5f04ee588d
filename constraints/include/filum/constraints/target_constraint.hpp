// TargetConstraint: a constraint that holds a point of its body to a PointTarget (fixed point,
// point on axis, point on plane, clamp, sliding point). Applications reach the target through
// this interface, without naming the concrete constraint, to steer it between steps
// (PointTarget::steer: a tool moved by a script or a device; Python's Scene.steer).
#pragma once

#include "filum/constraints/point_target.hpp"

namespace filum::constraints {

class TargetConstraint {
 public:
  virtual ~TargetConstraint() = default;
  virtual const PointTarget& target() const = 0;
  /// Changing the target changes what the constraint's rows hold from the next step on.
  virtual PointTarget& target() = 0;
};

}  // namespace filum::constraints
