#include "filum/constraints/spline_junction_constraint.hpp"

#include <array>
#include <cmath>

#include "filum/constraints/release_schedule.hpp"
#include "filum/constraints/curve_lookup.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/spline_curve.hpp"

namespace filum::constraints {

namespace {

/// Basis values of derivative order k (0, 1, 2) in a row.
const std::array<double, geometry::BasisRow::kMaxSupport>& derivative(const geometry::BasisRow& row, int k) {
  return k == 0 ? row.value : k == 1 ? row.d1 : row.d2;
}

/// Σ_j b_j^(k) x_j.
Vec3 combine(const geometry::BasisRow& row, int k, ConstPointsRef x) {
  const auto& w = derivative(row, k);
  Vec3 p = Vec3::Zero();
  for (int j = 0; j < row.count; ++j) p += w[j] * x.row(row.first + j).transpose();
  return p;
}

}  // namespace

SplineJunctionConstraint::SplineJunctionConstraint(std::string other, double abscissa, double other_abscissa,
                                                   int continuity, std::optional<double> ratio,
                                                   Baumgarte stabilization)
    : other_path_(std::move(other)),
      abscissa_(abscissa),
      other_abscissa_(other_abscissa),
      continuity_(continuity),
      requested_ratio_(ratio),
      baumgarte_(stabilization) {}

std::unique_ptr<SplineJunctionConstraint> SplineJunctionConstraint::fromParams(const Params& p) {
  const std::string other = p.string("other");
  if (other.empty()) p.fail("other", "the path of the node holding the other spline");
  const double s1 = p.has("abscissa") ? p.abscissa("abscissa") : 1.0;
  const double s2 = p.has("other_abscissa") ? p.abscissa("other_abscissa") : 0.0;
  int continuity = 2;
  if (p.has("continuity")) {
    const nlohmann::json& c = p.raw("continuity");
    if (!c.is_number_integer() || c.get<long>() < 0 || c.get<long>() > 2)
      p.fail("continuity", "a continuity order 0, 1 or 2 (C0: position, C1: + tangent, C2: + curvature)");
    continuity = c.get<int>();
  }
  std::optional<double> ratio;
  if (p.has("ratio")) ratio = p.positive({"ratio", "1"});
  auto junction = std::make_unique<SplineJunctionConstraint>(other, s1, s2, continuity, ratio, Baumgarte::fromParams(p));
  junction->other_where_ = p.where("other");
  readReleaseTime(p, *junction);
  return junction;
}

void SplineJunctionConstraint::init(const Scene& scene) {
  const CurveBody& own = requireCurve(body(), *this);
  other_ = &findCurve(scene, other_path_, other_where_.empty() ? origin() + "/other" : other_where_, *this);
  if (other_ == &own && abscissa_ == other_abscissa_)
    throw SceneError(other_where_.empty() ? origin() : other_where_,
                     "two different points to join (" + describe() + " joins a body to itself at one abscissa)",
                     "the same abscissa " + describeJson(abscissa_));
  own_point_.attach(own, abscissa_);
  other_point_.attach(*other_, other_abscissa_);
  if (requested_ratio_) {
    ratio_ = *requested_ratio_;
  } else {
    // ρ = |P1'(s1)| / |P2'(s2)| at t = 0 (only matters from C1 on).
    const double t1 = geometry::curveTangent(own_point_.row(), own.initialPositions()).norm();
    const double t2 = geometry::curveTangent(other_point_.row(), other_->initialPositions()).norm();
    if (continuity_ >= 1 && !(t1 > 0.0 && t2 > 0.0))
      throw SceneError(origin(), "a 'ratio' for " + describe() + " (an initial tangent at the junction is zero)",
                       "|P1'| = " + describeJson(t1) + ", |P2'| = " + describeJson(t2));
    ratio_ = continuity_ >= 1 ? t1 / t2 : 1.0;
  }
  baumgarte_.init(scene);
}

void SplineJunctionConstraint::jump(const SceneState& s, int order, Vec3& g, Vec3& dg) const {
  // g_k = P1^(k)(s1) − ρ^k P2^(k)(s2) and its time derivative (same weights on velocities).
  const double scale = std::pow(ratio_, order);
  const geometry::BasisRow &row1 = own_point_.row(), &row2 = other_point_.row();
  g = combine(row1, order, body().block(s.q)) - scale * combine(row2, order, other_->block(s.q));
  dg = combine(row1, order, body().block(s.v)) - scale * combine(row2, order, other_->block(s.v));
}

void SplineJunctionConstraint::buildRows(const SceneState& s, ConstraintRows& rows) const {
  for (int order = 0; order <= continuity_; ++order) {
    Vec3 g, dg;
    jump(s, order, g, dg);
    const Vec3 rhs = baumgarte_.term(g, dg);
    const double scale = std::pow(ratio_, order);
    const geometry::BasisRow &row1 = own_point_.row(), &row2 = other_point_.row();
    const auto& w1 = derivative(row1, order);
    const auto& w2 = derivative(row2, order);
    rows.beginAnchor();
    for (int j = 0; j < row1.count; ++j) rows.addAnchorPoint(own_point_.firstPoint() + j, w1[j]);
    for (int j = 0; j < row2.count; ++j) rows.addAnchorPoint(other_point_.firstPoint() + j, -scale * w2[j]);
    for (int axis = 0; axis < 3; ++axis) rows.addAnchoredRow(Vec3::Unit(axis), rhs[axis]);
  }
}

void SplineJunctionConstraint::violation(const SceneState& s, VecX& g, int first) const {
  for (int order = 0; order <= continuity_; ++order) {
    Vec3 gk, dgk;
    jump(s, order, gk, dgk);
    g.segment<3>(first + 3 * order) = gk;
  }
}

}  // namespace filum::constraints
