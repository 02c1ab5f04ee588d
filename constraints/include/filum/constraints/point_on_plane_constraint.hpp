// PointOnPlaneConstraint: the point of abscissa s of a spline stays on the plane through the
// target X(t) with unit normal n (paper Fig. 1a, the red plane): 1 row,
//   g(q, t) = nᵀ (P(s, t) − X(t)) = 0,
// the point slides freely in the plane (bilateral: it is held on both sides). The normal is
// fixed in space; X(t) is fixed, scripted or a point of another spline (point_target.hpp).
// Rows and Baumgarte terms as in projected_point_constraint.hpp with D = n.
#pragma once

#include <memory>

#include "filum/constraints/projected_point_constraint.hpp"
#include "filum/core/params.hpp"

namespace filum::constraints {

class PointOnPlaneConstraint final : public ProjectedPointConstraint {
 public:
  /// normal: non-zero (normalized here).
  PointOnPlaneConstraint(double abscissa, const Vec3& normal, PointTarget target,
                         Baumgarte stabilization = Baumgarte());

  /// "abscissa": s, "normal": [x,y,z] (non-zero), "target"/"path" (a point of the plane,
  /// default: initial P(s)), "stabilization": ω (1/s).
  static std::unique_ptr<PointOnPlaneConstraint> fromParams(const Params& p);

  std::string typeName() const override { return "PointOnPlaneConstraint"; }
  const Vec3& normal() const { return directions().front(); }
};

}  // namespace filum::constraints
