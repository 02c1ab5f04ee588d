#include "filum/constraints/sliding_point_constraint.hpp"

#include <algorithm>

#include "filum/constraints/projected_point_constraint.hpp"
#include "filum/constraints/release_schedule.hpp"
#include "filum/constraints/curve_lookup.hpp"
#include "filum/core/scene.hpp"
#include "filum/geometry/spline_curve.hpp"

namespace filum::constraints {

SlidingPointConstraint::SlidingPointConstraint(double abscissa, PointTarget target, double friction,
                                               Baumgarte stabilization)
    : initial_abscissa_(abscissa), target_(std::move(target)), friction_(friction), baumgarte_(stabilization) {}

std::unique_ptr<SlidingPointConstraint> SlidingPointConstraint::fromParams(const Params& p) {
  const double s = p.abscissa("abscissa");
  const double friction = p.nonNegative({"friction", "N·s/m"}, 0.0);
  auto c = std::make_unique<SlidingPointConstraint>(s, PointTarget::fromParams(p), friction, Baumgarte::fromParams(p));
  readReleaseTime(p, *c);
  return c;
}

void SlidingPointConstraint::init(const Scene& scene) {
  spline_ = &requireCurve(body(), *this);
  target_.init(scene, *this, geometry::curvePoint(spline_->basis(), spline_->initialPositions(), initial_abscissa_),
               body(), -1.0 /* s moves: no abscissa of its own to compare */);
  baumgarte_.init(scene);
  cuts_ = spline_->basis().cuts();  // a layout change binds the constraint again
  dt_ = scene.settings().dt;
}

SlidingPointConstraint::Local SlidingPointConstraint::evaluate(const SceneState& st) const {
  Local l;
  const double s = std::clamp(abscissa(st), 0.0, 1.0);
  const double sdot = abscissaRate(st);
  l.point.attach(*spline_, s);
  const ConstPointsMap q = body().block(st.q);
  const geometry::CurveDerivatives d = geometry::curveDerivatives(l.point.row(), q);
  l.p = d.point;
  l.t = d.first;
  l.pss = d.second;
  l.pdot = l.point.map(st.v);
  l.tdot = l.point.mapTangent(st.v);
  // g = P(s) − X, ġ = Ṗ(s) + P'(s) ṡ − Ẋ.
  const Vec3 g = l.p - target_.position(st);
  const Vec3 dg = l.pdot + l.t * sdot - target_.velocity(st);
  l.r = target_.knownAcceleration(st) - 2.0 * l.tdot * sdot - l.pss * (sdot * sdot) + baumgarte_.term(g, dg);
  return l;
}

Vec3 SlidingPointConstraint::gap(const SceneState& s) const {
  return geometry::curvePoint(spline_->basis(), body().block(s.q), std::clamp(abscissa(s), 0.0, 1.0)) -
         target_.position(s);
}

void SlidingPointConstraint::buildRows(const SceneState& st, ConstraintRows& rows) const {
  const Local l = evaluate(st);
  // Nᵀ (Σ_j b_j A_j − Ẍ) = Nᵀ r: anchor b_j(s) (and −b_k(s2) if the hole is attached).
  const auto [n1, n2] = orthonormalComplement(l.t.normalized());
  rows.beginAnchor();
  l.point.forEachWeight([&](int point, double weight) { rows.addAnchorPoint(point, weight); });
  target_.addToAnchor(rows);
  rows.addAnchoredRow(n1, n1.dot(l.r));
  rows.addAnchoredRow(n2, n2.dot(l.r));
}

void SlidingPointConstraint::extraAcceleration(const SceneState& st, VecX& a) const {
  if (!active()) {
    a[extraIndex()] = 0.0;
    return;
  }
  // Direct relation: s̈ = tᵀ (r − (Σ_j b_j A_j − Ẍ)) / |t|².
  const Local l = evaluate(st);
  const Vec3 acc = l.point.map(a) - target_.attachedAcceleration(a);
  a[extraIndex()] = l.t.dot(l.r - acc) / l.t.squaredNorm();
}

void SlidingPointConstraint::violation(const SceneState& s, VecX& g, int first) const {
  g.segment<3>(first) = gap(s);
}

void SlidingPointConstraint::addForce(const SceneState& st, VecX& B) const {
  if (friction_ == 0.0) return;
  // F = −η t̂ (t̂·u), u = Ṗ(s) − Ẋ: viscous friction of the hole on the sliding thread.
  const double s = std::clamp(abscissa(st), 0.0, 1.0);
  const BodyPoint point(*spline_, s);
  const Vec3 that = point.mapTangent(st.q).normalized();
  const Vec3 u = point.map(st.v) - target_.velocity(st);
  const Vec3 F = -friction_ * that * that.dot(u);
  point.addForce(F, B);
  target_.addReaction(F, B);
}

bool SlidingPointConstraint::releasedAt(const SceneState& s) const {
  // Released on schedule, or when the thread has slid out of the hole (s left [0, 1]), or a cut
  // end of it reaches the hole within twice this step.
  const double abscissa_now = abscissa(s);
  if (Constraint::releasedAt(s) || abscissa_now < 0.0 || abscissa_now > 1.0) return true;
  if (cut_release_time_ && s.time >= *cut_release_time_) return true;
  const double rate = abscissaRate(s), reach = 2.0 * std::abs(rate) * dt_;
  for (const double c : cuts_) {
    const double ahead = (c - abscissa_now) * (rate >= 0.0 ? 1.0 : -1.0);  // > 0: the cut lies ahead
    if (abscissa_now == c || (ahead >= 0.0 && ahead <= reach)) {
      cut_release_time_ = s.time;
      return true;
    }
  }
  return false;
}

}  // namespace filum::constraints
