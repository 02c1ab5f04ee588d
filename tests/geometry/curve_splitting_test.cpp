// Cutting a thread: splitting a curve into two independent curves that together are the original.
#include <gtest/gtest.h>

#include <random>

#include "filum/geometry/curve_splitting.hpp"
#include "filum/geometry/knot_vector.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "geometry/spline_test_support.hpp"

namespace filum::geometry {
namespace {

/// max over 1000 abscissas of |P(s) − P_piece(s')| with s' the piece's own abscissa.
double splitDeviation(const BSplineCurve& c, const SplitCurve& split, unsigned seed) {
  const NonUniformBSpline whole = c.basis(), before = split.before.basis(), after = split.after.basis();
  const double cut = split.split_abscissa;
  return test::maxDeviation([&](double s) { return curvePoint(whole, c.control_points, s); },
                            [&](double s) {
                              return s <= cut ? curvePoint(before, split.before.control_points, s / cut)
                                              : curvePoint(after, split.after.control_points, (s - cut) / (1 - cut));
                            },
                            1000, seed);
}

// Tolerance: the pieces' control points come from <= d + 1 exact insertions (convex combinations,
// a few ε each), and s/s* is rounded (shifting u by ~ε |u|, P by ~ε |u| |dP/du|, |dP/du| <= ~50):
// a few 1e-14 at most; 1e-12 as required.
constexpr double kReproduction = 1e-12;

TEST(CurveSplitting, TheTwoPiecesReproduceTheOriginal) {
  std::mt19937 rng(301);
  std::uniform_real_distribution<double> cut(0.01, 0.99);
  for (int d = 1; d <= 5; ++d)
    for (bool clamped : {true, false})
      for (int trial = 0; trial < 3; ++trial) {
        const BSplineCurve c = test::randomCurve(d, 2 * d + 3 + trial, clamped, rng, d);
        const double s = cut(rng);
        const SplitCurve split = splitCurve(c, s);
        EXPECT_NEAR(split.split_abscissa, s, 1e-15);
        // ñ = n + (d + 1 − m) control points in all, m the multiplicity u already had (0 here:
        // a random u is almost surely not a knot).
        EXPECT_EQ(split.before.controlPointCount() + split.after.controlPointCount(), c.controlPointCount() + d + 1);
        EXPECT_LE(splitDeviation(c, split, 11), kReproduction) << "d = " << d << " s = " << s;
        // The refinement matrix maps q (and so velocities) onto the two pieces' control points: the
        // same Oslo rows as the pieces, summed in the same order, so equal to round-off (1e-15).
        const Points mapped = split.refinement * c.control_points;
        EXPECT_LE((mapped.topRows(split.before.controlPointCount()) - split.before.control_points).cwiseAbs().maxCoeff(), 1e-15);
        EXPECT_LE((mapped.bottomRows(split.after.controlPointCount()) - split.after.control_points).cwiseAbs().maxCoeff(), 1e-15);
        // The two ends meet at the cut: P_before(1) = q̃_{a−1} = q̃_a = P_after(0).
        const NonUniformBSpline before = split.before.basis(), after = split.after.basis();
        EXPECT_LE((curvePoint(before, split.before.control_points, 1.0) - curvePoint(after, split.after.control_points, 0.0)).norm(),
                  kReproduction);
      }
}

TEST(CurveSplitting, AtAnExistingKnotOnlyTheMissingMultiplicityIsInserted) {
  // Cubic on clamped uniform knots 0 0 0 0 1 2 3 4 4 4 4 (7 points), cut at u = 2 (s = 1/2,
  // exact): 3 more copies of 2 make 10 points in all; the first piece has the knots
  // 0 0 0 0 1 2 2 2 2 (5 points) and the second 2 2 2 2 3 4 4 4 4 (5 points).
  std::mt19937 rng(302);
  const BSplineCurve c{3, clampedUniformKnots(3, 7), test::randomControlPoints(7, rng)};
  const SplitCurve split = splitCurve(c, 0.5);
  EXPECT_EQ(split.split_abscissa, 0.5);
  EXPECT_EQ(split.before.knots, (std::vector<double>{0, 0, 0, 0, 1, 2, 2, 2, 2}));
  EXPECT_EQ(split.after.knots, (std::vector<double>{2, 2, 2, 2, 3, 4, 4, 4, 4}));
  EXPECT_EQ(split.before.controlPointCount(), 5);
  EXPECT_EQ(split.after.controlPointCount(), 5);
  EXPECT_LE(splitDeviation(c, split, 12), kReproduction);
  // The outer control points are untouched: the cut is local.
  EXPECT_EQ(split.before.control_points.row(0), c.control_points.row(0));
  EXPECT_EQ(split.after.control_points.row(4), c.control_points.row(6));
}

TEST(CurveSplitting, CutsUniformCubicAndCatmullRomThreads) {
  std::mt19937 rng(303);
  const UniformCubicBSpline uniform(12);
  const CatmullRomSpline catmull(12);
  for (const CurveBasis* basis : std::initializer_list<const CurveBasis*>{&uniform, &catmull}) {
    const Points q = test::randomControlPoints(12, rng);
    const BSplineCurve c = toBSplineCurve(*basis, q);
    const SplitCurve split = splitCurve(c, 0.37);
    const NonUniformBSpline before = split.before.basis(), after = split.after.basis();
    const double cut = split.split_abscissa;
    EXPECT_LE(test::maxDeviation([&](double s) { return curvePoint(*basis, q, s); },
                                 [&](double s) {
                                   return s <= cut ? curvePoint(before, split.before.control_points, s / cut)
                                                   : curvePoint(after, split.after.control_points, (s - cut) / (1 - cut));
                                 },
                                 1000, 13),
              kReproduction)
        << basis->name();
  }
}

TEST(CurveSplitting, RejectsAbscissasOutsideTheOpenInterval) {
  const BSplineCurve c{3, clampedUniformKnots(3, 5), Points::Zero(5, 3)};
  EXPECT_THROW(splitCurve(c, 0.0), std::invalid_argument);
  EXPECT_THROW(splitCurve(c, 1.0), std::invalid_argument);
  EXPECT_THROW(splitCurve(c, std::nan("")), std::invalid_argument);
  EXPECT_THROW(splitCurveAtParameter(c, 5.0), std::invalid_argument);
}

}  // namespace
}  // namespace filum::geometry
