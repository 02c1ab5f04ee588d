// NUBS of degree 1..5: input checks, end interpolation of clamped curves, linear precision,
// continuity C^{d−m} at a knot of multiplicity m, breakpoints.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "filum/geometry/knot_vector.hpp"
#include "filum/geometry/nonuniform_bspline.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "geometry/spline_test_support.hpp"

namespace filum::geometry {
namespace {

TEST(NonUniformBSpline, RejectsBadInputWithAClearMessage) {
  auto message = [](auto&& make) {
    try {
      make();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message([] { NonUniformBSpline(0, {0, 0, 1, 1}); }).find("degree"), std::string::npos);
  EXPECT_NE(message([] { NonUniformBSpline(6, std::vector<double>(20, 0.0)); }).find("degree"), std::string::npos);
  EXPECT_NE(message([] { NonUniformBSpline(3, {0, 0, 0, 0, 1, 1, 1}); }).find("control points"), std::string::npos);
  EXPECT_NE(message([] { NonUniformBSpline(2, {0, 0, 0, 2, 1, 3, 3, 3}); }).find("non-decreasing"), std::string::npos);
  EXPECT_NE(message([] { NonUniformBSpline(2, {0, 0, 0, std::nan(""), 3, 3, 3}); }).find("finite"), std::string::npos);
  EXPECT_NE(message([] { NonUniformBSpline(1, {0, 0, 1, 1, 1, 2, 2}); }).find("multiplicity"), std::string::npos);
  // Unclamped with t_d = t_{d+1}: B_0 would vanish on the domain.
  EXPECT_NE(message([] { NonUniformBSpline(2, {0, 1, 2, 2, 3, 4, 5}); }).find("domain"), std::string::npos);
  EXPECT_NO_THROW(NonUniformBSpline(2, {0, 1, 2, 3, 4, 4, 5}));  // repeated knot outside the domain: fine
  EXPECT_NO_THROW(NonUniformBSpline(1, {0, 0, 1, 1, 2, 2}));  // C−1 interior knot: allowed (a cut)
}

TEST(NonUniformBSpline, ClampedCurvesInterpolateTheirEndPointsWithEndTangentsAlongTheFirstLeg) {
  // Clamped: P(0) = q_0, P(1) = q_{n−1} and dP/du(t_d) = d (q_1 − q_0)/(t_{d+1} − t_d) (the end
  // basis functions reduce to Bernstein ones); d/ds = (t_n − t_d) d/du. Round-off only: 1e-13
  // for |q| <= 1 and |P'| <= ~100.
  std::mt19937 rng(21);
  for (int d = 1; d <= 5; ++d) {
    const BSplineCurve c = test::randomCurve(d, 2 * d + 3, true, rng);
    const NonUniformBSpline basis = c.basis();
    const int n = c.controlPointCount();
    const std::vector<double>& t = c.knots;
    EXPECT_LE((curvePoint(basis, c.control_points, 0.0) - c.control_points.row(0).transpose()).norm(), 1e-15);
    EXPECT_LE((curvePoint(basis, c.control_points, 1.0) - c.control_points.row(n - 1).transpose()).norm(), 1e-15);
    const Vec3 expected = (t[n] - t[d]) * d / (t[d + 1] - t[d]) * (c.control_points.row(1) - c.control_points.row(0)).transpose();
    EXPECT_LE((curveDerivatives(basis, c.control_points, 0.0).first - expected).norm(), 1e-13 * (1 + expected.norm()));
  }
}

TEST(NonUniformBSpline, GrevilleAbscissasReproduceTheParameter) {
  // Linear precision (Marsden's identity): Σ_i ξ_i B_{i,d}(u) = u with the Greville abscissas
  // ξ_i = (t_{i+1} + ... + t_{i+d})/d, on any knot vector; and Σ B'_i ξ_i = 1. Round-off: a
  // few ε times Σ|B_i||ξ_i| (|ξ| <= 40 here) → 1e-13 for the value; for the derivative the terms
  // |B'_i ξ_i| reach d/gap · 40 ≈ 1000 (gaps >= 0.2) while their sum is 1: 6 · 1000 ε ≈ 1.3e-12, so
  // 1e-11; for the second derivative |B''_i| <= d(d − 1)/gap² ≈ 500: 1e-10.
  std::mt19937 rng(22);
  for (int d = 1; d <= 5; ++d)
    for (bool clamped : {true, false}) {
      const BSplineCurve c = test::randomCurve(d, 3 * d + 4, clamped, rng, d);
      const NonUniformBSpline basis = c.basis();
      const int n = c.controlPointCount();
      Points q = Points::Zero(n, 3);
      for (int i = 0; i < n; ++i) {
        for (int k = 1; k <= d; ++k) q(i, 0) += c.knots[i + k];
        q(i, 0) /= d;
      }
      std::uniform_real_distribution<double> u(0.0, 1.0);
      for (int k = 0; k < 200; ++k) {
        const double s = u(rng);
        BasisRow row;
        basis.evaluateAtParameter(basis.parameterAt(s), row);
        ASSERT_NEAR(curvePoint(row, q).x(), basis.parameterAt(s), 1e-13) << "d = " << d;
        ASSERT_NEAR(curveTangent(row, q).x(), 1.0, 1e-11) << "d = " << d;
        ASSERT_NEAR(curveSecondDerivative(row, q).x(), 0.0, 1e-10) << "d = " << d;
      }
    }
}

TEST(NonUniformBSpline, ContinuityAtAKnotIsDegreeMinusMultiplicity) {
  // At an interior knot of multiplicity m the curve is C^{d−m}: P^{(d−m)} is continuous (jump
  // over ±δ <= 2δ max|P^{(d−m+1)}|: at δ = 1e-9, with |P^{(k)}| <= ~1e4 for k <= 3
  // here (unit knot gaps, domain width 4, degree <= 5), that is < 2e-5 < 1e-4) and P^{(d−m+1)} jumps
  // by a generically non-zero amount (> 1e-3 here, random control points of size 1).
  // m = d + 1 makes the curve itself jump: the representation of a cut. continuity() reports
  // d − m. Only derivatives up to order 2 are available, so orders above 2 are not checked.
  std::mt19937 rng(23);
  for (int d = 1; d <= 5; ++d)
    for (int m = 1; m <= d + 1; ++m) {
      SCOPED_TRACE("d = " + std::to_string(d) + ", m = " + std::to_string(m));
      std::vector<double> t(d + 1, -2.0);
      t.push_back(-1.0);
      t.insert(t.end(), m, 0.0);
      t.push_back(1.0);
      t.insert(t.end(), d + 1, 2.0);
      const NonUniformBSpline basis(d, t);
      EXPECT_EQ(basis.continuity(), d - m);
      const Points q = test::randomControlPoints(basis.controlPointCount(), rng);
      const double s = basis.abscissaAt(0.0);
      auto derivative = [&](double x, int order) {
        const CurveDerivatives c = curveDerivatives(basis, q, x);
        return order == 0 ? c.point : (order == 1 ? c.first : c.second);
      };
      const int smooth = d - m;
      if (smooth >= 0 && smooth <= 2) {
        EXPECT_LT((derivative(s + 1e-9, smooth) - derivative(s - 1e-9, smooth)).norm(), 1e-4);
      }
      if (smooth + 1 <= 2) {
        EXPECT_GT((derivative(s + 1e-9, smooth + 1) - derivative(s - 1e-9, smooth + 1)).norm(), 1e-3);
      }
    }
}

TEST(NonUniformBSpline, BreakpointsAreTheDistinctDomainKnotsMappedToTheUnitInterval) {
  // Unclamped degree 2, knots 0 1 2 2 3 5 6 7 8: domain [t_2, t_6] = [2, 6], distinct knots
  // 2, 3, 5, 6 → s = 0, 1/4, 3/4, 1 (exact in binary).
  const NonUniformBSpline basis(2, {0, 1, 2, 3, 3, 5, 6, 7, 8});
  EXPECT_EQ(basis.controlPointCount(), 6);
  EXPECT_EQ(basis.domainStart(), 2.0);
  EXPECT_EQ(basis.domainEnd(), 6.0);
  EXPECT_EQ(basis.breakpoints(), (std::vector<double>{0.0, 0.25, 0.75, 1.0}));
  EXPECT_EQ(basis.continuity(), 0);  // the double knot 3 of a quadratic
  EXPECT_EQ(basis.parameterAt(0.25), 3.0);
  EXPECT_EQ(basis.abscissaAt(5.0), 0.75);
  EXPECT_EQ(basis.parameterAt(1.0), 6.0);
  EXPECT_EQ(basis.parameterAt(-1.0), 2.0);
}

TEST(NonUniformBSpline, DegreeOneIsThePolygonThroughItsControlPoints) {
  // Clamped degree 1 on knots t: P(t_{i+1}) = q_i and P is linear in between (hat functions).
  const std::vector<double> t{0, 0, 0.5, 2, 3, 3};
  const NonUniformBSpline basis(1, t);
  std::mt19937 rng(24);
  const Points q = test::randomControlPoints(4, rng);
  for (int i = 0; i < 4; ++i)
    EXPECT_LE((curvePoint(basis, q, basis.abscissaAt(t[i + 1])) - q.row(i).transpose()).norm(), 1e-15);
  const double mid = basis.abscissaAt(1.25);  // halfway between t_2 = 0.5 and t_3 = 2
  EXPECT_LE((curvePoint(basis, q, mid) - 0.5 * (q.row(1) + q.row(2)).transpose()).norm(), 1e-15);
  EXPECT_EQ(curveDerivatives(basis, q, mid).second, Vec3::Zero());
}

TEST(KnotVector, SpanSearchAndUniformVectors) {
  const std::vector<double> t{0, 0, 0, 1, 2, 2, 3, 3, 3};  // d = 2, n = 6
  EXPECT_EQ(findKnotSpan(2, 6, t, 0.0), 2);
  EXPECT_EQ(findKnotSpan(2, 6, t, 0.5), 2);
  EXPECT_EQ(findKnotSpan(2, 6, t, 1.0), 3);
  EXPECT_EQ(findKnotSpan(2, 6, t, 2.0), 5);   // the double knot: span [t_5, t_6)
  EXPECT_EQ(findKnotSpan(2, 6, t, 3.0), 5);   // u = t_n: last non-empty span
  EXPECT_EQ(findKnotSpan(2, 6, t, 9.0), 5);
  EXPECT_EQ(knotMultiplicity(t, 2.0), 2);
  EXPECT_EQ(knotMultiplicity(t, 1.5), 0);
  EXPECT_EQ(uniformKnots(2, 4), (std::vector<double>{-2, -1, 0, 1, 2, 3, 4}));
  EXPECT_EQ(clampedUniformKnots(2, 4), (std::vector<double>{0, 0, 0, 1, 2, 2, 2}));
  EXPECT_THROW(clampedUniformKnots(3, 3), std::invalid_argument);
}

}  // namespace
}  // namespace filum::geometry
