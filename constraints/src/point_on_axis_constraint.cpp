#include "filum/constraints/point_on_axis_constraint.hpp"

#include "filum/constraints/release_schedule.hpp"

namespace filum::constraints {

namespace {

std::vector<Vec3> acrossAxis(const Vec3& axis) {
  const auto [u, w] = orthonormalComplement(axis.normalized());
  return {u, w};
}

}  // namespace

PointOnAxisConstraint::PointOnAxisConstraint(double abscissa, const Vec3& axis, PointTarget target,
                                             Baumgarte stabilization)
    : ProjectedPointConstraint(abscissa, std::move(target), stabilization, acrossAxis(axis)),
      axis_(axis.normalized()) {}

std::unique_ptr<PointOnAxisConstraint> PointOnAxisConstraint::fromParams(const Params& p) {
  const double s = p.abscissa("abscissa");
  const Vec3 axis = p.vec3({"axis", "1"});
  if (!(axis.norm() > 0.0)) p.fail("axis", "a non-zero direction [x, y, z]");
  auto c = std::make_unique<PointOnAxisConstraint>(s, axis, PointTarget::fromParams(p), Baumgarte::fromParams(p));
  readReleaseTime(p, *c);
  return c;
}

}  // namespace filum::constraints
