// Catmull-Rom: interpolation of its control points, C1 only, negative lobes, end handling,
// phantom end points and the exact knot form (Bézier double knots).
#include <gtest/gtest.h>

#include <random>

#include "filum/geometry/bspline_curve.hpp"
#include "filum/geometry/catmull_rom_spline.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "geometry/spline_test_support.hpp"

namespace filum::geometry {
namespace {

TEST(CatmullRomSpline, InterpolatesItsInnerControlPoints) {
  // P((i − 1)/N) = q_i for i = 1..n−2. s = (i − 1)/N is rounded (relative error ε/2), so u = N s
  // is off by <= N ε and P by <= |dP/du| N ε <= 2 max|q| · 20 ε ≈ 1e-14 for |q| <= 1, N <= 20.
  for (int n : {4, 5, 12, 23}) {
    const CatmullRomSpline basis(n);
    std::mt19937 rng(n);
    const Points q = test::randomControlPoints(n, rng);
    for (int i = 1; i <= n - 2; ++i)
      EXPECT_LE((curvePoint(basis, q, basis.abscissaOfControlPoint(i)) - q.row(i).transpose()).norm(), 1e-14)
          << "n = " << n << " i = " << i;
    EXPECT_THROW(basis.abscissaOfControlPoint(0), std::invalid_argument);
    EXPECT_THROW(basis.abscissaOfControlPoint(n - 1), std::invalid_argument);
  }
}

TEST(CatmullRomSpline, TangentsAreCentralDifferencesAndContinuous) {
  // P'(s) at the junction through q_i is N (q_{i+1} − q_{i−1})/2 from both sides (C1): the
  // closed form is exact, so only round-off of O(N |q| ε) remains.
  const int n = 10;
  const CatmullRomSpline basis(n);
  std::mt19937 rng(2);
  const Points q = test::randomControlPoints(n, rng);
  const double N = n - 3;
  for (int i = 1; i <= n - 2; ++i) {
    const double s = basis.abscissaOfControlPoint(i);
    const Vec3 expected = 0.5 * N * (q.row(i + 1) - q.row(i - 1)).transpose();
    EXPECT_LE((curveDerivatives(basis, q, s).first - expected).norm(), 1e-13);
    // Left limit: evaluate the segment that ends there (t = 1 on segment i − 2).
    if (i >= 2) {
      BasisRow row;
      basis.evaluate(s - 1e-13, row);
      EXPECT_LE((curveTangent(row, q) - expected).norm(), 1e-9);  // + |P''| 1e-13 drift
    }
  }
}

TEST(CatmullRomSpline, SecondDerivativeJumpsAtJunctions) {
  // Only C1. From the closed form, d²b/dt² is (2, −5, 4, −1) at t = 0 and (−1, 4, −5, 2) at t = 1,
  // so at the junction through q_i
  //   P''(s+) = N² (2 q_{i−1} − 5 q_i + 4 q_{i+1} − q_{i+2}),  P''(s−) = N² (−q_{i−2} + 4 q_{i−1} − 5 q_i + 2 q_{i+1}),
  // generically different. We evaluate 1e-12 on either side: P'' moves by <= 1e-12 |P'''|
  // (|P'''| <= 24 N³ max|q| ≈ 5e3), so 1e-8 covers it.
  const int n = 9;
  const CatmullRomSpline basis(n);
  std::mt19937 rng(4);
  const Points q = test::randomControlPoints(n, rng);
  const double N = n - 3;
  for (int i = 2; i <= n - 3; ++i) {
    const double s = basis.abscissaOfControlPoint(i);
    const Vec3 right = N * N * (2 * q.row(i - 1) - 5 * q.row(i) + 4 * q.row(i + 1) - q.row(i + 2)).transpose();
    const Vec3 left = N * N * (-q.row(i - 2) + 4 * q.row(i - 1) - 5 * q.row(i) + 2 * q.row(i + 1)).transpose();
    EXPECT_LE((curveDerivatives(basis, q, s + 1e-12).second - right).norm(), 1e-8);
    EXPECT_LE((curveDerivatives(basis, q, s - 1e-12).second - left).norm(), 1e-8);
    EXPECT_GT((right - left).norm(), 1e-3 * N * N);  // a real jump, not round-off
  }
}

TEST(CatmullRomSpline, FunctionsDipToMinusTwoTwentySeventhsSoNoConvexHull) {
  // b_0(t) = −t(1 − t)²/2 has its minimum −2/27 at t = 1/3: Catmull-Rom is not non-negative
  // (the generic non-negativity test exempts it for this reason). Over 3000 samples the minimum
  // is within the sampling error (1/3000)² · |b''|/2 ≈ 1e-7 of −2/27, and never below it.
  const CatmullRomSpline basis(4);
  double lowest = 0.0;
  BasisRow row;
  for (int k = 0; k <= 3000; ++k) {
    basis.evaluate(k / 3000.0, row);
    for (int j = 0; j < 4; ++j) lowest = std::min(lowest, row.value[j]);
  }
  EXPECT_GE(lowest, -2.0 / 27 - 1e-15);
  EXPECT_LE(lowest, -2.0 / 27 + 1e-6);
}

TEST(CatmullRomSpline, ReproducesStraightLinesWithUniformSpacing) {
  // Linear precision: q_i = a + i h gives P(s) = q_1 + s (q_{n−2} − q_1) exactly (the cubic terms
  // cancel); round-off ~ 4ε·|q| ≈ 1e-14 with |q| <= 20.
  const int n = 12;
  const CatmullRomSpline basis(n);
  const Vec3 a(0.3, -1, 2), h(0.5, 0.25, -1);
  Points q(n, 3);
  for (int i = 0; i < n; ++i) q.row(i) = (a + i * h).transpose();
  for (int k = 0; k <= 100; ++k) {
    const double s = k / 100.0;
    const Vec3 expected = q.row(1).transpose() + s * (q.row(n - 2) - q.row(1)).transpose();
    EXPECT_LE((curvePoint(basis, q, s) - expected).norm(), 1e-13);
  }
}

TEST(CatmullRomSpline, PhantomEndPointsMakeTheCurvePassThroughEveryPoint) {
  std::mt19937 rng(8);
  const Points points = test::randomControlPoints(6, rng);
  const Points q = withPhantomEndPoints(points);
  ASSERT_EQ(q.rows(), 8);
  const CatmullRomSpline basis(8);
  for (int i = 0; i < 6; ++i)
    EXPECT_LE((curvePoint(basis, q, i / 5.0) - points.row(i).transpose()).norm(), 1e-14);
  // Reflected phantom ends: zero second difference at the ends of the control polygon.
  EXPECT_LE((q.row(0) - 2 * q.row(1) + q.row(2)).norm(), 1e-15);
  EXPECT_THROW(withPhantomEndPoints(points.topRows(1)), std::invalid_argument);
}

TEST(CatmullRomSpline, KnotFormReproducesTheCurve) {
  // toBSplineCurve writes each segment as a cubic Bézier and joins them with double knots; the
  // two evaluations differ by round-off: ~10 operations on |q| <= 1 → 1e-14.
  for (int n : {4, 5, 13}) {
    const CatmullRomSpline basis(n);
    std::mt19937 rng(30 + n);
    const Points q = test::randomControlPoints(n, rng);
    const BSplineCurve curve = toBSplineCurve(basis, q);
    EXPECT_EQ(curve.controlPointCount(), 2 * (n - 3) + 2);
    const NonUniformBSpline nubs = curve.basis();
    if (n > 4) {
      EXPECT_EQ(nubs.continuity(), 1);  // double interior knots of a cubic (none when n = 4)
    }
    const double error = test::maxDeviation([&](double s) { return curvePoint(basis, q, s); },
                                            [&](double s) { return curvePoint(nubs, curve.control_points, s); }, 1000, 1);
    EXPECT_LE(error, 1e-14) << "n = " << n;
  }
}

TEST(CatmullRomSpline, RejectsFewerThanFourControlPoints) {
  EXPECT_THROW(CatmullRomSpline(3), std::invalid_argument);
}

}  // namespace
}  // namespace filum::geometry
