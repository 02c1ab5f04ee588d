#include "filum/constraints/point_on_plane_constraint.hpp"

#include "filum/constraints/release_schedule.hpp"

namespace filum::constraints {

PointOnPlaneConstraint::PointOnPlaneConstraint(double abscissa, const Vec3& normal, PointTarget target,
                                               Baumgarte stabilization)
    : ProjectedPointConstraint(abscissa, std::move(target), stabilization, {normal.normalized()}) {}

std::unique_ptr<PointOnPlaneConstraint> PointOnPlaneConstraint::fromParams(const Params& p) {
  const double s = p.abscissa("abscissa");
  const Vec3 normal = p.vec3({"normal", "1"});
  if (!(normal.norm() > 0.0)) p.fail("normal", "a non-zero normal [x, y, z]");
  auto c = std::make_unique<PointOnPlaneConstraint>(s, normal, PointTarget::fromParams(p), Baumgarte::fromParams(p));
  readReleaseTime(p, *c);
  return c;
}

}  // namespace filum::constraints
