#include "filum/constraints/projected_point_constraint.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "filum/constraints/curve_lookup.hpp"
#include "filum/geometry/spline_curve.hpp"

namespace filum::constraints {

std::pair<Vec3, Vec3> orthonormalComplement(const Vec3& a) {
  // Cross a with the coordinate axis it is least aligned with: never nearly parallel.
  Eigen::Index axis = 0;
  a.cwiseAbs().minCoeff(&axis);
  const Vec3 u = a.cross(Vec3::Unit(axis)).normalized();
  return {u, a.cross(u)};
}

ProjectedPointConstraint::ProjectedPointConstraint(double abscissa, PointTarget target, Baumgarte baumgarte,
                                                   std::vector<Vec3> directions)
    : abscissa_(abscissa), target_(std::move(target)), baumgarte_(baumgarte), directions_(std::move(directions)) {}

void ProjectedPointConstraint::init(const Scene& scene) {
  const CurveBody& spline = requireCurve(body(), *this);
  point_.attach(spline, abscissa_);
  target_.init(scene, *this, geometry::curvePoint(point_.row(), spline.initialPositions()), body(), abscissa_);
  baumgarte_.init(scene);
}

Vec3 ProjectedPointConstraint::gap(const SceneState& s) const {
  return point_.map(s.q) - target_.position(s);
}

void ProjectedPointConstraint::buildRows(const SceneState& s, ConstraintRows& rows) const {
  // g = P(s) − X, ġ = Ṗ(s) − Ẋ; the stabilizing acceleration is projected on every d_i.
  const Vec3 g = gap(s);
  const Vec3 dg = point_.map(s.v) - target_.velocity(s);
  const Vec3 rhs = target_.knownAcceleration(s) + baumgarte_.term(g, dg);
  // One anchor: b_j(s) on the body, −b_k(s2) on an attached target.
  rows.beginAnchor();
  point_.forEachWeight([&](int point, double weight) { rows.addAnchorPoint(point, weight); });
  target_.addToAnchor(rows);
  for (const Vec3& d : directions_) rows.addAnchoredRow(d, d.dot(rhs));
}

void ProjectedPointConstraint::violation(const SceneState& s, VecX& g, int first) const {
  const Vec3 gap3 = gap(s);
  for (std::size_t i = 0; i < directions_.size(); ++i) g[first + static_cast<int>(i)] = directions_[i].dot(gap3);
}

}  // namespace filum::constraints
