// Exact knot insertion (Boehm, Oslo): the refined curve is the same curve.
#include <gtest/gtest.h>

#include <random>

#include "filum/geometry/knot_insertion.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "geometry/spline_test_support.hpp"

namespace filum::geometry {
namespace {

/// Random knots strictly inside the domain, some equal to existing knots (raising their
/// multiplicity, never above d + 1).
std::vector<double> randomNewKnots(const BSplineCurve& c, int count, std::mt19937& rng) {
  const int d = c.degree, n = c.controlPointCount();
  std::uniform_real_distribution<double> u(c.knots[d], c.knots[n]), coin(0.0, 1.0);
  std::vector<double> out;
  std::vector<double> all = c.knots;
  while (static_cast<int>(out.size()) < count) {
    double x = u(rng);
    if (coin(rng) < 0.3) x = c.knots[std::uniform_int_distribution<int>(d + 1, n - 1)(rng)];
    if (!(x > c.knots[d] && x < c.knots[n])) continue;
    if (std::count(all.begin(), all.end(), x) >= d + 1) continue;
    out.push_back(x);
    all.push_back(x);
  }
  return out;
}

double curveDistance(const BSplineCurve& a, const BSplineCurve& b, unsigned seed) {
  const NonUniformBSpline ba = a.basis(), bb = b.basis();
  return test::maxDeviation([&](double s) { return curvePoint(ba, a.control_points, s); },
                            [&](double s) { return curvePoint(bb, b.control_points, s); }, 1000, seed);
}

// Tolerance of the reproduction tests. Each new control point is an affine (in fact convex)
// combination of old ones with weights in [0, 1], so it carries an error of a few ε·max|q| per
// insertion level; evaluating either curve adds (d + 1)·few ε. With |q| <= 1 and at most 12
// successive Boehm passes the difference stays below ~100 ε ≈ 2e-14: 1e-12 is a wide margin.
constexpr double kReproduction = 1e-12;

TEST(KnotInsertion, BoehmLeavesTheCurveUnchanged) {
  std::mt19937 rng(101);
  for (int d = 1; d <= 5; ++d)
    for (bool clamped : {true, false})
      for (int trial = 0; trial < 4; ++trial) {
        const BSplineCurve c = test::randomCurve(d, d + 2 + 3 * trial, clamped, rng, d);
        for (double u : randomNewKnots(c, 3, rng)) {
          const BSplineCurve refined = insertKnot(c, u);
          ASSERT_EQ(refined.controlPointCount(), c.controlPointCount() + 1);
          EXPECT_LE(curveDistance(c, refined, 5), kReproduction) << "d = " << d << " u = " << u;
        }
      }
}

TEST(KnotInsertion, OsloInsertsManyKnotsAtOnceAndAgreesWithRepeatedBoehm) {
  // Same curve to kReproduction, and the same control points as inserting one at a time
  // (the refined representation is unique: the refined B-splines are independent on the domain).
  std::mt19937 rng(102);
  for (int d = 1; d <= 5; ++d)
    for (bool clamped : {true, false})
      for (int trial = 0; trial < 4; ++trial) {
        const BSplineCurve c = test::randomCurve(d, d + 2 + 2 * trial, clamped, rng, d);
        const std::vector<double> extra = randomNewKnots(c, 2 + 3 * trial, rng);
        const BSplineCurve oslo = insertKnots(c, extra);
        ASSERT_EQ(oslo.controlPointCount(), c.controlPointCount() + static_cast<int>(extra.size()));
        EXPECT_LE(curveDistance(c, oslo, 6), kReproduction) << "d = " << d;
        BSplineCurve boehm = c;
        for (double u : extra) boehm = insertKnot(boehm, u);
        EXPECT_EQ(boehm.knots, oslo.knots);
        EXPECT_LE((boehm.control_points - oslo.control_points).cwiseAbs().maxCoeff(), kReproduction);
      }
}

TEST(KnotInsertion, RefinementMatrixIsLocalNonNegativeAndSumsToOne) {
  // Rows of A are discrete B-splines α^d_{·,j}: >= 0, <= d + 1 non-zeros, Σ_i α_{i,j} = 1
  // (refinement of the partition of unity). Every factor of the recurrence is >= 0, so the
  // entries are >= 0 exactly in floating point; the sums are 1 up to d levels of convex
  // combinations, ~2dε: 1e-14.
  std::mt19937 rng(103);
  for (int d = 1; d <= 5; ++d)
    for (bool clamped : {true, false}) {
      const BSplineCurve c = test::randomCurve(d, 3 * d + 2, clamped, rng, d);
      const std::vector<double> refined = refinedKnotVector(d, c.knots, randomNewKnots(c, 7, rng));
      const SparseMatrix A = knotInsertionMatrix(d, c.knots, refined);
      ASSERT_EQ(A.rows(), static_cast<Eigen::Index>(refined.size()) - d - 1);
      ASSERT_EQ(A.cols(), c.controlPointCount());
      for (int j = 0; j < A.outerSize(); ++j) {
        double sum = 0.0;
        int count = 0;
        for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
          sum += it.value();
          ++count;
          EXPECT_GE(it.value(), 0.0);
        }
        EXPECT_NEAR(sum, 1.0, 1e-14);
        EXPECT_LE(count, d + 1);
      }
      // A q is what insertKnots computes.
      const Points viaMatrix = A * c.control_points;
      BSplineCurve refinedCurve{d, refined, viaMatrix};
      EXPECT_LE(curveDistance(c, refinedCurve, 7), kReproduction);
    }
}

TEST(KnotInsertion, WorksOnUniformCubicAndCatmullRomThroughTheirKnotForm) {
  std::mt19937 rng(104);
  const UniformCubicBSpline uniform(9);
  const CatmullRomSpline catmull(9);
  for (const CurveBasis* basis : std::initializer_list<const CurveBasis*>{&uniform, &catmull}) {
    const Points q = test::randomControlPoints(9, rng);
    const BSplineCurve c = toBSplineCurve(*basis, q);
    const BSplineCurve refined = insertKnots(c, randomNewKnots(c, 10, rng));
    const NonUniformBSpline nubs = refined.basis();
    EXPECT_LE(test::maxDeviation([&](double s) { return curvePoint(*basis, q, s); },
                                 [&](double s) { return curvePoint(nubs, refined.control_points, s); }, 1000, 8),
              kReproduction)
        << basis->name();
  }
}

TEST(KnotInsertion, RejectsKnotsOutsideTheDomainOrAboveFullMultiplicity) {
  const BSplineCurve c{2, {0, 0, 0, 1, 2, 2, 2}, Points::Zero(4, 3)};
  EXPECT_THROW(insertKnot(c, 0.0), std::invalid_argument);   // domain end
  EXPECT_THROW(insertKnot(c, 2.5), std::invalid_argument);   // outside
  EXPECT_THROW(insertKnot(c, 1.0, 3), std::invalid_argument);  // multiplicity 4 > d + 1
  EXPECT_NO_THROW(insertKnot(c, 1.0, 2));                       // multiplicity 3 = d + 1
  EXPECT_THROW(insertKnots(c, {1.0, 1.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(insertKnots(c, {0.5, -1.0}), std::invalid_argument);
  BSplineCurve bad = c;
  bad.knots = {0, 0, 0, 2, 1, 2, 2};
  EXPECT_THROW(insertKnot(bad, 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace filum::geometry
