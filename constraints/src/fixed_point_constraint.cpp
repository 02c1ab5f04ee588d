#include "filum/constraints/fixed_point_constraint.hpp"

#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum::constraints {

FixedPointConstraint::FixedPointConstraint(double abscissa, std::optional<Vec3> target, ScriptedPath path,
                                           std::optional<double> stabilization)
    : abscissa_(abscissa), target_(target), path_(std::move(path)), omega_(stabilization) {}

std::unique_ptr<FixedPointConstraint> FixedPointConstraint::fromParams(const Params& p) {
  const double s = p.abscissa("abscissa");
  std::optional<Vec3> target;
  if (p.has("target")) target = p.vec3("target");
  ScriptedPath path;
  if (p.has("path")) path = ScriptedPath::fromParams(p, "path");
  if (target && !path.empty()) p.fail("path", "either 'target' or 'path', not both");
  std::optional<double> omega;
  if (p.has("stabilization")) omega = p.nonNegative("stabilization", 0.0);
  return std::make_unique<FixedPointConstraint>(s, target, std::move(path), omega);
}

void FixedPointConstraint::init(const Scene& scene) {
  const auto* spline = dynamic_cast<const mechanics::DynamicSpline*>(&body());
  if (!spline) throw SceneError(origin(), "a DynamicSpline body for " + describe(), body().describe());
  spline->basis().evaluate(abscissa_, row_);
  if (!target_ && path_.empty()) target_ = geometry::curvePoint(row_, spline->initialPositions());
  if (!omega_) omega_ = 0.1 / scene.settings().dt;
}

void FixedPointConstraint::buildRows(const SceneState& s, ConstraintRows& rows) const {
  const ConstPointsMap q = body().block(s.q);
  const ConstPointsMap v = body().block(s.v);
  const Vec3 g = geometry::curvePoint(row_, q) - targetAt(s.time);
  const Vec3 target_velocity = path_.empty() ? Vec3::Zero() : path_.velocity(s.time);
  const Vec3 dg = geometry::curvePoint(row_, v) - target_velocity;
  const double omega = *omega_;
  const Vec3 rhs = -2.0 * omega * dg - omega * omega * g;  // Ẍ = 0 on a scripted segment
  for (int axis = 0; axis < 3; ++axis) {
    for (int j = 0; j < row_.count; ++j)
      rows.addTerm(body().offset() + row_.first + j, row_.value[j] * Vec3::Unit(axis));
    rows.endRow(rhs[axis]);
  }
}

void FixedPointConstraint::violation(const SceneState& s, VecX& g, int first) const {
  g.segment<3>(first) = geometry::curvePoint(row_, body().block(s.q)) - targetAt(s.time);
}

}  // namespace filum::constraints
