#include "filum/constraints/clamp_constraint.hpp"

#include <tuple>

#include "filum/constraints/projected_point_constraint.hpp"
#include "filum/constraints/release_schedule.hpp"
#include "filum/constraints/curve_lookup.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/spline_curve.hpp"

namespace filum::constraints {

ClampConstraint::ClampConstraint(double abscissa, PointTarget target, std::optional<Vec3> direction,
                                 Baumgarte stabilization)
    : abscissa_(abscissa), target_(std::move(target)), requested_direction_(direction), baumgarte_(stabilization) {}

std::unique_ptr<ClampConstraint> ClampConstraint::fromParams(const Params& p) {
  const double s = p.abscissa("abscissa");
  std::optional<Vec3> direction;
  if (p.has({"direction", "1"})) {
    direction = p.vec3({"direction", "1"});
    if (!(direction->norm() > 0.0)) p.fail("direction", "a non-zero direction [x, y, z]");
  }
  auto c = std::make_unique<ClampConstraint>(s, PointTarget::fromParams(p), direction, Baumgarte::fromParams(p));
  readReleaseTime(p, *c);
  return c;
}

void ClampConstraint::init(const Scene& scene) {
  const CurveBody& spline = requireCurve(body(), *this);
  point_.attach(spline, abscissa_);
  const geometry::BasisRow& row = point_.row();
  const Points& q0 = spline.initialPositions();
  target_.init(scene, *this, geometry::curvePoint(row, q0), body(), abscissa_);
  const Vec3 d = requested_direction_ ? *requested_direction_ : geometry::curveTangent(row, q0);
  if (!(d.norm() > 0.0))
    throw SceneError(origin(), "a 'direction' for " + describe() + " (the initial tangent at the abscissa is zero)",
                     "P'(s) = 0");
  direction_ = d.normalized();
  std::tie(u_, w_) = orthonormalComplement(direction_);
  baumgarte_.init(scene);
}

void ClampConstraint::buildRows(const SceneState& s, ConstraintRows& rows) const {
  const ConstPointsMap q = body().block(s.q);
  const ConstPointsMap v = body().block(s.v);
  const geometry::BasisRow& row = point_.row();
  const int offset = point_.firstPoint();

  // Position: g_p = P(s) − X, ġ_p = Ṗ(s) − Ẋ; anchor b_j(s) (and −b_k(s2) if attached).
  const Vec3 gp = geometry::curvePoint(row, q) - target_.position(s);
  const Vec3 dgp = geometry::curvePoint(row, v) - target_.velocity(s);
  const Vec3 rp = target_.knownAcceleration(s) + baumgarte_.term(gp, dgp);
  rows.beginAnchor();
  point_.forEachWeight([&](int point, double weight) { rows.addAnchorPoint(point, weight); });
  target_.addToAnchor(rows);
  for (int axis = 0; axis < 3; ++axis) rows.addAnchoredRow(Vec3::Unit(axis), rp[axis]);

  // Direction: g_d = [u w]ᵀ P'(s), ġ_d = [u w]ᵀ Ṗ'(s); anchor b'_j(s).
  const Vec3 t = geometry::curveTangent(row, q);
  const Vec3 dt = geometry::curveTangent(row, v);
  rows.beginAnchor();
  for (int j = 0; j < row.count; ++j) rows.addAnchorPoint(offset + j, row.d1[j]);
  rows.addAnchoredRow(u_, baumgarte_.term(u_.dot(t), u_.dot(dt)));
  rows.addAnchoredRow(w_, baumgarte_.term(w_.dot(t), w_.dot(dt)));
}

void ClampConstraint::violation(const SceneState& s, VecX& g, int first) const {
  const ConstPointsMap q = body().block(s.q);
  const geometry::BasisRow& row = point_.row();
  g.segment<3>(first) = geometry::curvePoint(row, q) - target_.position(s);
  const Vec3 t = geometry::curveTangent(row, q);
  g[first + 3] = u_.dot(t);
  g[first + 4] = w_.dot(t);
}

}  // namespace filum::constraints
