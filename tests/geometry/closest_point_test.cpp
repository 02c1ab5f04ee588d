// Closest point on a curve: global search + Newton against a dense brute-force search.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "filum/geometry/closest_point.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "geometry/spline_test_support.hpp"

namespace filum::geometry {
namespace {

TEST(ClosestPoint, MatchesADenseBruteForceSearch) {
  // Brute force: the distance at 40001 equally spaced abscissas. Newton's answer must be at least
  // as close (to round-off: 1e-12), i.e. it found the global minimum, not a local one; and where
  // it lands inside (0, 1), away from the knots where a C0 or C−1 curve has a corner or a jump, the
  // first-order condition (P − x)·P' = 0 holds to round-off relative to |P − x| |P'| (1e-9 allows
  // for the Newton stopping test on s).
  std::mt19937 rng(501);
  const auto bases = test::allTestBases();
  for (const auto& [label, basis, non_negative] : bases) {
    if (label.find("n4") != std::string::npos || label.find("d1") != std::string::npos) continue;
    SCOPED_TRACE(label);
    const Points q = test::randomControlPoints(basis->controlPointCount(), rng);
    const Points dense = sampleCurve(*basis, q, 40001);
    std::uniform_real_distribution<double> box(-1.2, 1.2);
    for (int k = 0; k < 12; ++k) {
      const Vec3 x(box(rng), box(rng), box(rng));
      const double brute = (dense.rowwise() - x.transpose()).rowwise().norm().minCoeff();
      const ClosestPoint c = closestPoint(*basis, q, x);
      EXPECT_LE(c.distance, brute + 1e-12) << "x = " << x.transpose();
      EXPECT_NEAR((curvePoint(*basis, q, c.s) - x).norm(), c.distance, 1e-15);
      const std::vector<double> pieces = basis->breakpoints();
      const bool at_corner = basis->continuity() < 1 && std::any_of(pieces.begin(), pieces.end(), [&](double b) {
                               return std::abs(b - c.s) < 1e-11;
                             });
      if (c.s > 0.0 && c.s < 1.0 && !at_corner) {
        const CurveDerivatives d = curveDerivatives(*basis, q, c.s);
        EXPECT_LE(std::abs((d.point - x).dot(d.first)), 1e-9 * (1 + c.distance * d.first.norm()));
      }
    }
  }
}

TEST(ClosestPoint, FindsPointsOnTheCurveAndClampsBeyondItsEnds) {
  // A point of the curve is its own closest point (distance at round-off, 1e-14); a point beyond
  // the end along the end tangent projects onto the end itself, s = 1 exactly (clamped).
  std::mt19937 rng(502);
  const NonUniformBSpline basis(3, clampedUniformKnots(3, 9));
  const Points q = test::randomControlPoints(9, rng);
  for (double s : {0.0, 0.13, 0.5, 0.77, 1.0}) {
    const ClosestPoint c = closestPoint(basis, q, curvePoint(basis, q, s));
    EXPECT_LE(c.distance, 1e-14);
  }
  // A convex planar arc y = 0.1 x²: beyond either end along the tangent the distance decreases
  // all the way to the end point, which is the global minimum.
  Points arc(9, 3);
  for (int i = 0; i < 9; ++i) arc.row(i) << i, 0.1 * i * i, 0;
  const CurveDerivatives end = curveDerivatives(basis, arc, 1.0);
  EXPECT_EQ(closestPoint(basis, arc, end.point + 0.5 * end.first.normalized()).s, 1.0);
  const CurveDerivatives start = curveDerivatives(basis, arc, 0.0);
  EXPECT_EQ(closestPoint(basis, arc, start.point - 0.5 * start.first.normalized()).s, 0.0);
}

TEST(ClosestPoint, RejectsBadArguments) {
  const UniformCubicBSpline basis(5);
  EXPECT_THROW(closestPoint(basis, Points::Zero(4, 3), Vec3::Zero()), std::invalid_argument);
  EXPECT_THROW(closestPoint(basis, Points::Zero(5, 3), Vec3::Zero(), 0), std::invalid_argument);
  EXPECT_THROW(closestPoint(basis, Points::Zero(5, 3), Vec3(std::nan(""), 0, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace filum::geometry
