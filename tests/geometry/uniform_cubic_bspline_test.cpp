// The uniform cubic B-spline of the paper (§2): closed-form values, its knot form, C2 but not C3.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "filum/geometry/catmull_rom_spline.hpp"
#include "filum/geometry/knot_vector.hpp"
#include "filum/geometry/nonuniform_bspline.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/geometry/uniform_cubic_bspline.hpp"
#include "geometry/spline_test_support.hpp"

namespace filum::geometry {
namespace {

TEST(UniformCubicBSpline, ValuesAndDerivativesAtTheStartOfASegment) {
  // At t = 0: b = (1, 4, 1, 0)/6, db/dt = (−1, 0, 1, 0)/2, d²b/dt² = (1, −2, 1, 0); with N = 5
  // segments d/ds = N d/dt. All are exact binary fractions times small integers: exact up to one
  // rounding of 1/6 (1e-16).
  const UniformCubicBSpline basis(8);
  const double N = 5;
  BasisRow row;
  basis.evaluate(0.0, row);
  EXPECT_EQ(row.first, 0);
  EXPECT_EQ(row.count, 4);
  const double value[4] = {1.0 / 6, 2.0 / 3, 1.0 / 6, 0.0};
  const double d1[4] = {-0.5 * N, 0.0, 0.5 * N, 0.0};
  const double d2[4] = {N * N, -2 * N * N, N * N, 0.0};
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(row.value[j], value[j], 1e-16);
    EXPECT_NEAR(row.d1[j], d1[j], 1e-15);
    EXPECT_NEAR(row.d2[j], d2[j], 1e-13);
  }
  // Interior segment start s = 2/N: same pattern shifted to first = 2.
  basis.evaluate(2.0 / N, row);
  EXPECT_EQ(row.first, 2);
  for (int j = 0; j < 4; ++j) EXPECT_NEAR(row.value[j], value[j], 1e-15);
  // End: P(1) = (q_{n−3} + 4 q_{n−2} + q_{n−1})/6.
  basis.evaluate(1.0, row);
  EXPECT_EQ(row.first, 4);
  EXPECT_NEAR(row.value[1], 1.0 / 6, 1e-16);
  EXPECT_NEAR(row.value[2], 2.0 / 3, 1e-16);
  EXPECT_NEAR(row.value[3], 1.0 / 6, 1e-16);
}

TEST(UniformCubicBSpline, IsTheNubsOnUniformKnots) {
  // Same functions as Cox–de Boor on t_i = i − 3 (domain [0, N]): values, d/ds and d²/ds² agree
  // to round-off. Values <= 1 (error ~1e-16), b' ~ N = 17 (1e-14), b'' ~ N² ≈ 300 (1e-12).
  for (int n : {4, 5, 20}) {
    const UniformCubicBSpline uniform(n);
    const NonUniformBSpline nubs(3, uniformKnots(3, n));
    EXPECT_EQ(uniform.breakpoints().size(), nubs.breakpoints().size());
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    BasisRow a, b;
    for (int k = 0; k < 1000; ++k) {
      const double s = k == 0 ? 1.0 : u(rng);
      uniform.evaluate(s, a);
      nubs.evaluate(s, b);
      ASSERT_EQ(a.first, b.first);
      for (int j = 0; j < 4; ++j) {
        ASSERT_NEAR(a.value[j], b.value[j], 1e-14);
        ASSERT_NEAR(a.d1[j], b.d1[j], 1e-12);
        ASSERT_NEAR(a.d2[j], b.d2[j], 1e-10);
      }
    }
  }
}

TEST(UniformCubicBSpline, SecondDerivativeIsContinuousButThirdJumps) {
  // C2: P'' at knot ± δ differs by about 2δ|P'''| → 0 linearly; P''' = (P''(s+δ) − P''(s))/δ is
  // piecewise constant and jumps at the knot for generic control points (by Σ Δ³q ≠ 0).
  const int n = 9;
  const UniformCubicBSpline basis(n);
  std::mt19937 rng(5);
  const Points q = test::randomControlPoints(n, rng);
  const double knot = 3.0 / (n - 3);
  auto second = [&](double s) { return curveDerivatives(basis, q, s).second; };
  double previous = 1e300;
  for (double delta : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
    const double jump = (second(knot + delta) - second(knot - delta)).norm();
    EXPECT_LT(jump, 0.2 * previous + 1e-10) << "delta = " << delta;  // decreases ~10x per decade
    previous = jump;
  }
  const double delta = 1e-4;
  const Vec3 third_left = (second(knot - delta) - second(knot - 2 * delta)) / delta;
  const Vec3 third_right = (second(knot + 2 * delta) - second(knot + delta)) / delta;
  // Exact: P''' jumps by N³ (q_{j−1} − 4 q_j + 6 q_{j+1} − 4 q_{j+2} + q_{j+3}) (fourth difference).
  const double N = n - 3;
  const Vec3 expected = N * N * N * (q.row(2) - 4 * q.row(3) + 6 * q.row(4) - 4 * q.row(5) + q.row(6)).transpose();
  EXPECT_LE((third_right - third_left - expected).norm(), 1e-6 * expected.norm());
}

// A NaN abscissa (a diverging Runge-Kutta stage of a sliding point) evaluates the first piece
// instead of control point INT_MIN (a segmentation fault); the scene then reports the non-finite
// state and rolls the step back. Catmull-Rom shares the piece lookup.
TEST(UniformCubicBSpline, ANaNAbscissaStaysWithinTheControlPoints) {
  const UniformCubicBSpline basis(10);
  BasisRow row, first;
  basis.evaluate(std::numeric_limits<double>::quiet_NaN(), row);
  basis.evaluate(0.0, first);
  EXPECT_EQ(row.first, first.first);
  EXPECT_EQ(row.count, 4);
  for (int j = 0; j < 4; ++j) EXPECT_EQ(row.value[j], first.value[j]);
  const CatmullRomSpline catmull_rom(10);
  catmull_rom.evaluate(std::numeric_limits<double>::quiet_NaN(), row);
  EXPECT_GE(row.first, 0);
  EXPECT_LE(row.first + row.count, 10);
}

TEST(UniformCubicBSpline, RejectsFewerThanFourControlPoints) {
  EXPECT_THROW(UniformCubicBSpline(3), std::invalid_argument);
  EXPECT_NO_THROW(UniformCubicBSpline(4));
}

}  // namespace
}  // namespace filum::geometry
