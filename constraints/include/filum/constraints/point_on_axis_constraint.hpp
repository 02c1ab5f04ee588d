// PointOnAxisConstraint: the point of abscissa s of a spline stays on the line through the
// target X(t) with unit direction a (paper Fig. 1a, the blue cylinder): 2 rows,
//   g(q, t) = [u w]ᵀ (P(s, t) − X(t)) = 0,   (a, u, w) orthonormal,
// so the point slides freely along a and is held across it. The axis direction is fixed in
// space; X(t) is fixed, scripted or a point of another spline (point_target.hpp). Rows and
// Baumgarte terms as in projected_point_constraint.hpp with D = [u w].
#pragma once

#include <memory>

#include "filum/constraints/projected_point_constraint.hpp"
#include "filum/core/params.hpp"

namespace filum::constraints {

class PointOnAxisConstraint final : public ProjectedPointConstraint {
 public:
  /// axis: non-zero direction (normalized here).
  PointOnAxisConstraint(double abscissa, const Vec3& axis, PointTarget target, Baumgarte stabilization = Baumgarte());

  /// "abscissa": s, "axis": [x,y,z] (non-zero), "target"/"path" (a point of the axis, default:
  /// initial P(s)), "stabilization": ω (1/s).
  static std::unique_ptr<PointOnAxisConstraint> fromParams(const Params& p);

  std::string typeName() const override { return "PointOnAxisConstraint"; }
  const Vec3& axis() const { return axis_; }

 private:
  Vec3 axis_;
};

}  // namespace filum::constraints
