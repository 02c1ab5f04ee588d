// Arc length: exact on straight lines, converging on a helix, inverse map, equal spacing.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "filum/geometry/arc_length.hpp"
#include "filum/geometry/gauss_legendre.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "geometry/spline_test_support.hpp"

namespace filum::geometry {
namespace {

TEST(ArcLength, StraightLineSplineHasItsChordLength) {
  // Control points on a line, increasing along it (B-splines), equally spaced (Catmull-Rom):
  // P moves monotonically along the line, so its length is |P(1) − P(0)|. On each piece |P'| is
  // then a polynomial of degree d − 1 <= 4, integrated exactly by G_8: only round-off remains,
  // ~ (pieces · 8 terms) ε L <= 1e-13 for L ≈ 2. Required: 1e-12.
  const Vec3 direction = Vec3(1, -2, 0.5).normalized();
  // (Curves broken by a knot of multiplicity d + 1 are skipped: their jump is not arc length.)
  for (const auto& [label, basis, non_negative] : test::allTestBases()) {
    if (basis->continuity() < 0) continue;
    SCOPED_TRACE(label);
    const int n = basis->controlPointCount();
    std::mt19937 rng(401);
    std::uniform_real_distribution<double> step(0.05, 0.3);
    Points q(n, 3);
    double x = -0.7;
    for (int i = 0; i < n; ++i) {
      x += non_negative ? step(rng) : 0.2;
      q.row(i) = (Vec3(0.1, 0.2, 0.3) + x * direction).transpose();
    }
    const double chord = (curvePoint(*basis, q, 1.0) - curvePoint(*basis, q, 0.0)).norm();
    EXPECT_NEAR(curveLength(*basis, q), chord, 1e-12);
    EXPECT_NEAR(ArcLengthParameterization(*basis, q).totalLength(), chord, 1e-12);
  }
}

/// Uniform cubic B-spline whose control points are samples of the helix
/// (cos θ, sin θ, c θ), θ ∈ [0, 4π], one sample every 4π/(n − 1).
struct SampledHelix {
  static constexpr double kPitch = 0.2;
  explicit SampledHelix(int n) : basis(n), q(n, 3), step(4 * std::numbers::pi / (n - 1)) {
    for (int i = 0; i < n; ++i) q.row(i) << std::cos(i * step), std::sin(i * step), kPitch * i * step;
  }
  UniformCubicBSpline basis;
  Points q;
  double step;
};

TEST(ArcLength, AdaptiveQuadratureConvergesOnAHelixLikeCurve) {
  // Reference: relative tolerance 1e-15. (1) One G_k per piece converges geometrically in k (|P'|
  // is analytic on each piece; the error of G_k ~ (2k)!-scaled 2k-th derivative times (h/2)^{2k}):
  // every two extra nodes gain at least a factor 100 (odd and even k alternate in quality), until
  // round-off (1e-14 L). (2) The adaptive rule meets every requested tolerance, |L_τ − L| <= τ L, doing more
  // work for a smaller τ.
  const SampledHelix helix(30);
  const double reference = curveLength(helix.basis, helix.q, 1e-15);
  const std::vector<double> pieces = helix.basis.breakpoints();
  std::vector<double> errors;
  for (int k = 1; k <= 8; ++k) {
    const QuadratureRule rule = gaussLegendre(k);
    double length = 0.0;
    for (std::size_t p = 0; p + 1 < pieces.size(); ++p)
      length += integrate(rule, pieces[p], pieces[p + 1], [&](double s) {
        return curveDerivatives(helix.basis, helix.q, s).first.norm();
      });
    errors.push_back(std::abs(length - reference));
  }
  for (std::size_t k = 2; k < errors.size(); ++k)
    EXPECT_LT(errors[k], std::max(0.01 * errors[k - 2], 1e-14 * reference)) << k + 1 << " nodes per piece";
  EXPECT_LT(errors.back(), 1e-14 * reference);
  int work = 0;
  for (double tolerance : {1e-4, 1e-6, 1e-8, 1e-10, 1e-12}) {
    const ArcLengthParameterization arc(helix.basis, helix.q, tolerance);
    EXPECT_LE(std::abs(arc.totalLength() - reference), tolerance * reference) << "tolerance " << tolerance;
    EXPECT_GE(arc.intervalCount(), work);
    work = arc.intervalCount();
  }
}

TEST(ArcLength, SplineOfDenserHelixSamplesConvergesQuadraticallyToTheHelixLength) {
  // The uniform cubic B-spline of samples x(θ_i) is x + (Δθ²/6) x'' + O(Δθ⁴): the helix shrunk to
  // radius ≈ 1 − Δθ²/6, so its length over [θ_1, θ_{n−2}] differs from the helix's by O(Δθ²).
  // Doubling the samples divides the error by 4 (we accept 3.5..4.5).
  double previous_error = 0.0;
  for (int n : {41, 81, 161, 321}) {
    const SampledHelix helix(n);
    const double theta = (n - 3) * helix.step;  // from θ_1 to θ_{n−2}
    const double exact = theta * std::sqrt(1 + SampledHelix::kPitch * SampledHelix::kPitch);
    const double error = std::abs(curveLength(helix.basis, helix.q) - exact);
    if (previous_error > 0.0) {
      EXPECT_GT(previous_error / error, 3.5) << "n = " << n;
      EXPECT_LT(previous_error / error, 4.5) << "n = " << n;
    }
    previous_error = error;
  }
}

TEST(ArcLength, InverseMapIsTheInverse) {
  // L(s(ℓ)) = ℓ: Newton converges to round-off and L is accurate to τ = 1e-12 L: 1e-12 L plus the
  // few-ε round-off of the sums; and s(L(s)) = s where the curve moves (speed > 0 everywhere here),
  // to 1e-12 L / min|P'| ≈ 1e-11.
  std::mt19937 rng(402);
  for (const auto& [label, basis, non_negative] : test::allTestBases()) {
    SCOPED_TRACE(label);
    const Points q = test::randomControlPoints(basis->controlPointCount(), rng);
    const ArcLengthParameterization arc(*basis, q);
    const double total = arc.totalLength();
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 100; ++k) {
      const double length = u(rng) * total;
      const double s = arc.abscissaAtLength(length);
      EXPECT_NEAR(arc.lengthAt(s), length, 2e-12 * total);
    }
    EXPECT_EQ(arc.abscissaAtLength(-1.0), 0.0);
    EXPECT_EQ(arc.abscissaAtLength(2 * total), 1.0);
    EXPECT_EQ(arc.lengthAt(0.0), 0.0);
    EXPECT_NEAR(arc.lengthAt(1.0), total, 1e-15 * total);
  }
}

TEST(ArcLength, EqualCurvilinearSpacing) {
  // Collinear control points unevenly spaced on a NUBS with uneven knots: s is far from
  // proportional to length, but the samples at equal curvilinear spacing are equally spaced in
  // space, to the arc-length accuracy (1e-12 L).
  const NonUniformBSpline basis(3, {0, 0, 0, 0, 0.1, 0.15, 0.7, 1, 1, 1, 1});
  Points q(7, 3);
  const double x[7] = {0, 0.05, 0.1, 0.8, 1.5, 1.6, 3};
  for (int i = 0; i < 7; ++i) q.row(i) << x[i], 2 * x[i], 0;
  const ArcLengthParameterization arc(basis, q);
  const Points p = arc.equallySpacedPoints(25);
  const double spacing = arc.totalLength() / 24;
  for (int k = 0; k + 1 < 25; ++k) EXPECT_NEAR((p.row(k + 1) - p.row(k)).norm(), spacing, 1e-12 * arc.totalLength());
  // On a curved thread: consecutive samples are equally far apart along the curve.
  const SampledHelix helix(20);
  const ArcLengthParameterization curved(helix.basis, helix.q);
  const std::vector<double> s = curved.equallySpacedAbscissas(50);
  for (int k = 0; k + 1 < 50; ++k)
    EXPECT_NEAR(curved.lengthAt(s[k + 1]) - curved.lengthAt(s[k]), curved.totalLength() / 49, 2e-12 * curved.totalLength());
}

TEST(ArcLength, RejectsBadArguments) {
  const UniformCubicBSpline basis(5);
  const Points q = Points::Zero(5, 3);
  EXPECT_THROW(curveLength(basis, Points::Zero(4, 3)), std::invalid_argument);
  EXPECT_THROW(curveLength(basis, q, 0.0), std::invalid_argument);
  EXPECT_THROW(curveLength(basis, q, 1.0), std::invalid_argument);
  EXPECT_EQ(curveLength(basis, q), 0.0);  // a thread collapsed to a point
  EXPECT_THROW(ArcLengthParameterization(basis, q).equallySpacedAbscissas(1), std::invalid_argument);
}

}  // namespace
}  // namespace filum::geometry
