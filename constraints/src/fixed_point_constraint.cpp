#include "filum/constraints/fixed_point_constraint.hpp"

#include "filum/constraints/release_schedule.hpp"

namespace filum::constraints {

namespace {

std::vector<Vec3> identityDirections() { return {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()}; }

PointTarget skeletonTarget(std::optional<Vec3> target, geometry::ScriptedPath path) {
  if (!path.empty()) return PointTarget::scripted(std::move(path));
  return target ? PointTarget::fixed(*target) : PointTarget();
}

}  // namespace

FixedPointConstraint::FixedPointConstraint(double abscissa, PointTarget target, Baumgarte stabilization)
    : ProjectedPointConstraint(abscissa, std::move(target), stabilization, identityDirections()) {}

FixedPointConstraint::FixedPointConstraint(double abscissa, std::optional<Vec3> target, geometry::ScriptedPath path,
                                           std::optional<double> stabilization)
    : FixedPointConstraint(abscissa, skeletonTarget(target, std::move(path)), Baumgarte(stabilization)) {}

std::unique_ptr<FixedPointConstraint> FixedPointConstraint::fromParams(const Params& p) {
  const double s = p.abscissa("abscissa");
  auto c = std::make_unique<FixedPointConstraint>(s, PointTarget::fromParams(p), Baumgarte::fromParams(p));
  readReleaseTime(p, *c);
  return c;
}

}  // namespace filum::constraints
