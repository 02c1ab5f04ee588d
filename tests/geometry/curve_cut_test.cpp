// Cut curves at the basis level (CurveBasis::cuts, evaluateFromLeft, strands): a knot of
// multiplicity d + 1 splits the curve into strands ([Lenoir talk 2008], "local C-1 continuity => cut").
//   - no basis function straddles the cut: the row from the left ends at point a − 1, the row
//     from the right starts at point a;
//   - at the instant of the cut the curve is unchanged: both limits are P(u) of the curve before
//     the knots were inserted, and they are the two strands' own ends (geometry::splitCurve);
//   - everywhere else evaluateFromLeft is evaluate (the same span), and at the knots of the
//     uniform bases the left limits are those of the segment that ends there.
// Tolerances: a point is a sum of d + 1 <= 6 products of weights in [−1, 1] with coordinates
// |q| <= 1, so two evaluations of the same point agree to a few ε (bound 1e-15); the limit
// checks compare rows of the same polynomial at t = 1 and t = 0 of adjacent segments, equal in
// exact arithmetic up to the order of continuity.
#include <cmath>

#include <gtest/gtest.h>

#include "filum/geometry/catmull_rom_spline.hpp"
#include "filum/geometry/curve_splitting.hpp"
#include "filum/geometry/knot_insertion.hpp"
#include "filum/geometry/nonuniform_bspline.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/geometry/uniform_cubic_bspline.hpp"

namespace filum::geometry {
namespace {

/// A bent cubic curve on uniform knots (clamped), 9 control points in the unit box.
BSplineCurve bentCurve() {
  BSplineCurve c;
  c.degree = 3;
  c.knots = {0, 0, 0, 0, 1, 2, 3, 4, 5, 6, 6, 6, 6};
  c.control_points.resize(9, 3);
  for (int i = 0; i < 9; ++i) c.control_points.row(i) << 0.1 * i, std::sin(0.7 * i), 0.3 * std::cos(1.3 * i);
  return c;
}

Vec3 combine(const BasisRow& row, const Points& q, const std::array<double, BasisRow::kMaxSupport>& w) {
  Vec3 p = Vec3::Zero();
  for (int j = 0; j < row.count; ++j) p += w[j] * q.row(row.first + j).transpose();
  return p;
}

TEST(CurveCut, AKnotOfMultiplicityDegreePlusOneIsACutWithTwoStrands) {
  const BSplineCurve curve = bentCurve();
  const double u = 2.5;  // not a knot yet: 4 insertions
  const BSplineCurve cut = insertKnots(curve, std::vector<double>(4, u));
  const NonUniformBSpline basis(cut.degree, cut.knots);
  const double s = u / 6.0;
  ASSERT_EQ(basis.cuts().size(), 1u);
  EXPECT_NEAR(basis.cuts()[0], s, 1e-16);
  EXPECT_EQ(basis.continuity(), -1);
  const std::vector<Strand> pieces = strands(basis);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_EQ(pieces[0].begin, 0.0);
  EXPECT_EQ(pieces[0].end, basis.cuts()[0]);
  EXPECT_EQ(pieces[1].begin, basis.cuts()[0]);
  EXPECT_EQ(pieces[1].end, 1.0);

  // No function straddles the cut: the left row ends at a − 1, the right row starts at a.
  BasisRow left, right;
  basis.evaluateFromLeft(basis.cuts()[0], left);
  basis.evaluate(basis.cuts()[0], right);
  const SplitCurve split = splitCurve(curve, s);
  const int a = static_cast<int>(split.before.control_points.rows());
  EXPECT_EQ(left.first + left.count - 1, a - 1);
  EXPECT_EQ(right.first, a);
  // Both ends are P(u) of the uncut curve, and each is its strand's own end (an interpolated
  // control point of the clamped strands).
  const Vec3 p = curvePoint(NonUniformBSpline(curve.degree, curve.knots), curve.control_points, s);
  const Vec3 p_left = combine(left, cut.control_points, left.value), p_right = combine(right, cut.control_points, right.value);
  EXPECT_LE((p_left - p).norm(), 1e-15);
  EXPECT_LE((p_right - p).norm(), 1e-15);
  EXPECT_LE((p_left - split.before.control_points.bottomRows(1).transpose()).norm(), 1e-15);
  EXPECT_LE((p_right - split.after.control_points.topRows(1).transpose()).norm(), 1e-15);
  // Tangents from either side are those of the uncut curve too (C² there before the cut).
  BasisRow whole;
  NonUniformBSpline(curve.degree, curve.knots).evaluate(s, whole);
  const Vec3 t = combine(whole, curve.control_points, whole.d1);
  EXPECT_LE((combine(left, cut.control_points, left.d1) - t).norm(), 1e-13 * t.norm());
  EXPECT_LE((combine(right, cut.control_points, right.d1) - t).norm(), 1e-13 * t.norm());
  // Once the strands move apart, the two ends are different points: move strand 2 alone.
  Points moved = cut.control_points;
  moved.bottomRows(moved.rows() - a).rowwise() += Vec3(0, 0, 1).transpose();
  EXPECT_LE((combine(left, moved, left.value) - p).norm(), 1e-15);
  EXPECT_NEAR((combine(right, moved, right.value) - p).norm(), 1.0, 1e-15);
}

TEST(CurveCut, FromTheLeftIsEvaluateInsideSpansAndAtKnotsBelowMultiplicityDegreePlusOne) {
  const BSplineCurve curve = bentCurve();
  const NonUniformBSpline basis(curve.degree, curve.knots);
  EXPECT_TRUE(basis.cuts().empty());
  ASSERT_EQ(strands(basis).size(), 1u);
  for (int k = 0; k <= 60; ++k) {
    const double s = (k + 0.37) / 61.0;  // never a knot
    BasisRow a, b;
    basis.evaluate(s, a);
    basis.evaluateFromLeft(s, b);
    EXPECT_EQ(a.first, b.first);
    for (int j = 0; j < a.count; ++j) {
      EXPECT_EQ(a.value[j], b.value[j]);
      EXPECT_EQ(a.d2[j], b.d2[j]);
    }
  }
  // At an interior knot (multiplicity 1, C²) the two rows belong to adjacent spans and give the
  // same point, tangent and second derivative.
  for (int knot = 1; knot <= 5; ++knot) {
    BasisRow a, b;
    basis.evaluate(knot / 6.0, a);
    basis.evaluateFromLeft(knot / 6.0, b);
    EXPECT_EQ(b.first + 1, a.first) << "knot " << knot;
    const Points& q = curve.control_points;
    EXPECT_LE((combine(a, q, a.value) - combine(b, q, b.value)).norm(), 1e-15);
    EXPECT_LE((combine(a, q, a.d1) - combine(b, q, b.d1)).norm(), 1e-13 * combine(a, q, a.d1).norm());
    EXPECT_LE((combine(a, q, a.d2) - combine(b, q, b.d2)).norm(), 1e-12 * combine(a, q, a.d2).norm());
  }
}

TEST(CurveCut, UniformBasesHaveNoCutsAndTheirLeftRowsEndTheSegmentBefore) {
  const UniformCubicBSpline bspline(10);
  const CatmullRomSpline catmull(10);
  Points q(10, 3);
  for (int i = 0; i < 10; ++i) q.row(i) << 0.1 * i, std::sin(0.9 * i), 0.2 * i * i / 100.0;
  for (const CurveBasis* basis : {static_cast<const CurveBasis*>(&bspline), static_cast<const CurveBasis*>(&catmull)}) {
    EXPECT_TRUE(basis->cuts().empty()) << basis->name();
    for (int knot = 1; knot < 7; ++knot) {
      BasisRow a, b;
      basis->evaluate(knot / 7.0, a);
      basis->evaluateFromLeft(knot / 7.0, b);
      EXPECT_EQ(b.first + 1, a.first) << basis->name() << " knot " << knot;
      // Both bases are C¹: the point and the tangent agree from both sides.
      EXPECT_LE((combine(a, q, a.value) - combine(b, q, b.value)).norm(), 1e-15);
      EXPECT_LE((combine(a, q, a.d1) - combine(b, q, b.d1)).norm(), 1e-13 * combine(a, q, a.d1).norm());
      // P'' too for the C² B-spline; Catmull-Rom's P'' jumps at knots (its left value, the end of
      // the segment before, is in general not the next segment's start), so it is not compared.
      const double jump = (combine(a, q, a.d2) - combine(b, q, b.d2)).norm();
      if (basis == &bspline) {
        EXPECT_LE(jump, 1e-12 * combine(a, q, a.d2).norm()) << "knot " << knot;
      }
    }
    // At s = 0 the left row is the first segment's, at s = 1 the last's (as evaluate).
    BasisRow a, b;
    basis->evaluate(0.0, a);
    basis->evaluateFromLeft(0.0, b);
    EXPECT_EQ(a.first, b.first);
    basis->evaluate(1.0, a);
    basis->evaluateFromLeft(1.0, b);
    EXPECT_EQ(a.first, b.first);
  }
}

TEST(CurveCut, ACutAbscissaRoundTripsOntoItsKnot) {
  // cuts() reports s = (u − t_d)/(t_n − t_d) rounded; evaluating at that s must pick the spans
  // on either side of the knot, not a span of round-off width next to it: u = 1/3 of a domain
  // that does not divide it exactly.
  BSplineCurve curve = bentCurve();
  for (double& t : curve.knots) t = 0.1 + 0.7 * t;  // domain [0.1, 4.3]
  const double u = 0.1 + 0.7 * (6.0 / 3.0 + 1e-3);
  const BSplineCurve cut = insertKnots(curve, std::vector<double>(4, u));
  const NonUniformBSpline basis(cut.degree, cut.knots);
  ASSERT_EQ(basis.cuts().size(), 1u);
  BasisRow left, right;
  basis.evaluateFromLeft(basis.cuts()[0], left);
  basis.evaluate(basis.cuts()[0], right);
  EXPECT_EQ(left.first + left.count, right.first);
  EXPECT_DOUBLE_EQ(left.value[left.count - 1], 1.0);  // clamped strand ends interpolate
  EXPECT_DOUBLE_EQ(right.value[0], 1.0);
}

}  // namespace
}  // namespace filum::geometry
