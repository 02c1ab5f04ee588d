// Knot removal: exact when the knot is removable, otherwise an approximation whose reported
// bound really bounds the deviation.
#include <gtest/gtest.h>

#include <random>

#include "filum/geometry/knot_insertion.hpp"
#include "filum/geometry/knot_removal.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "geometry/spline_test_support.hpp"

namespace filum::geometry {
namespace {

double curveDistance(const BSplineCurve& a, const BSplineCurve& b, int samples, unsigned seed) {
  const NonUniformBSpline ba = a.basis(), bb = b.basis();
  return test::maxDeviation([&](double s) { return curvePoint(ba, a.control_points, s); },
                            [&](double s) { return curvePoint(bb, b.control_points, s); }, samples, seed);
}

TEST(KnotRemoval, RemovingAJustInsertedKnotIsExact) {
  // Insert u then remove it: the least-squares system is consistent, so the residual (the bound)
  // and the recovered control points are at round-off, a few ε·|q| through an O(1)-conditioned
  // d × (d − 1) QR: 1e-13.
  std::mt19937 rng(201);
  for (int d = 1; d <= 5; ++d)
    for (bool clamped : {true, false}) {
      const BSplineCurve c = test::randomCurve(d, 2 * d + 4, clamped, rng, 1);
      std::uniform_real_distribution<double> pick(c.knots[d], c.knots[c.controlPointCount()]);
      const double u = pick(rng);
      const KnotRemoval removal = removeKnot(insertKnot(c, u), u);
      EXPECT_EQ(removal.removed, 1);
      EXPECT_LE(removal.error_bound, 1e-13) << "d = " << d;
      EXPECT_EQ(removal.curve.knots, c.knots);
      EXPECT_LE((removal.curve.control_points - c.control_points).cwiseAbs().maxCoeff(), 1e-13) << "d = " << d;
    }
}

TEST(KnotRemoval, TheReportedBoundBoundsTheDeviation) {
  // For a generic curve removal is an approximation: the bound is positive and the measured
  // max |P_old − P_new| over 2000 abscissas does not exceed it (convex-hull argument, exact up
  // to evaluation round-off of 1e-14).
  std::mt19937 rng(202);
  for (int d = 1; d <= 5; ++d)
    for (bool clamped : {true, false}) {
      const BSplineCurve c = test::randomCurve(d, 2 * d + 4, clamped, rng, d);
      const std::vector<double> inner = distinctDomainKnots(d, c.controlPointCount(), c.knots);
      for (std::size_t k = 1; k + 1 < inner.size(); ++k) {
        const KnotRemoval removal = removeKnot(c, inner[k]);
        EXPECT_GT(removal.error_bound, 1e-6);
        const double deviation = curveDistance(c, removal.curve, 2000, 9);
        EXPECT_LE(deviation, removal.error_bound + 1e-14) << "d = " << d << " u = " << inner[k];
        EXPECT_GE(deviation, 0.05 * removal.error_bound);  // and it is not wildly pessimistic
      }
    }
}

TEST(KnotRemoval, SimplificationUndoesRefinementWithinTheTolerance) {
  // A cubic refined with 10 knots carries no more information than before: simplification with a
  // tolerance of 1e-10 (far above the ~1e-15 per-removal bounds) removes all 10 again and the
  // result is within its accumulated bound of the original.
  std::mt19937 rng(203);
  const BSplineCurve c = test::randomCurve(3, 7, true, rng, 1);
  std::uniform_real_distribution<double> pick(c.knots[3], c.knots[7]);
  std::vector<double> extra;
  for (int k = 0; k < 10; ++k) extra.push_back(pick(rng));
  const BSplineCurve refined = insertKnots(c, extra);
  const KnotRemoval simplified = simplifyCurve(refined, 1e-10);
  EXPECT_GE(simplified.removed, 10);
  EXPECT_LE(simplified.error_bound, 1e-10);
  EXPECT_LE(curveDistance(refined, simplified.curve, 1000, 10), simplified.error_bound + 1e-14);
  // With a zero tolerance a generic curve keeps all its knots.
  EXPECT_EQ(simplifyCurve(c, 0.0).removed, 0);
}

TEST(KnotRemoval, RejectsValuesThatAreNotInteriorKnots) {
  const BSplineCurve c{2, {0, 0, 0, 1, 2, 2, 2}, Points::Zero(4, 3)};
  EXPECT_THROW(removeKnot(c, 0.5), std::invalid_argument);
  EXPECT_THROW(removeKnot(c, 0.0), std::invalid_argument);
  EXPECT_THROW(removeKnot(c, 2.0), std::invalid_argument);
  EXPECT_NO_THROW(removeKnot(c, 1.0));
  EXPECT_THROW(simplifyCurve(c, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace filum::geometry
