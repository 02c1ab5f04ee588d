// Rotation-minimizing frames (double reflection) and Frenet frames.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "filum/geometry/frenet_frame.hpp"
#include "filum/geometry/rotation_minimizing_frames.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/geometry/spline_point_mapping.hpp"  // uniformAbscissas
#include "geometry/spline_test_support.hpp"

namespace filum::geometry {
namespace {

void expectOrthonormal(const CurveFrame& f, double tolerance) {
  EXPECT_NEAR(f.tangent.norm(), 1.0, tolerance);
  EXPECT_NEAR(f.normal.norm(), 1.0, tolerance);
  EXPECT_NEAR(f.binormal.norm(), 1.0, tolerance);
  EXPECT_NEAR(f.tangent.dot(f.normal), 0.0, tolerance);
  EXPECT_NEAR(f.tangent.dot(f.binormal), 0.0, tolerance);
  EXPECT_NEAR(f.normal.dot(f.binormal), 0.0, tolerance);
  EXPECT_LE((f.tangent.cross(f.normal) - f.binormal).norm(), tolerance);
}

TEST(RotationMinimizingFrames, AreOrthonormalAlongRandomCurves) {
  // Reflections are orthogonal maps and r is re-projected ⊥ t and renormalised at every step, so
  // over 1000 frames the error stays at a few ε (1e-12 required). The tangent is P'/|P'|.
  std::mt19937 rng(601);
  for (const auto& [label, basis, non_negative] : test::allTestBases()) {
    if (basis->degree() < 2) continue;  // tangent discontinuous at the knots of a polygon
    SCOPED_TRACE(label);
    const Points q = test::randomControlPoints(basis->controlPointCount(), rng);
    const std::vector<double> s = uniformAbscissas(1000);
    const std::vector<CurveFrame> frames = rotationMinimizingFrames(*basis, q, s, Vec3(0.3, 0.1, 1));
    ASSERT_EQ(frames.size(), 1000u);
    for (int k = 0; k < 1000; k += 7) {
      expectOrthonormal(frames[k], 1e-12);
      const CurveDerivatives c = curveDerivatives(*basis, q, s[k]);
      EXPECT_LE((frames[k].tangent - c.first.normalized()).norm(), 1e-12);
      EXPECT_LE((frames[k].origin - c.point).norm(), 1e-15);
    }
  }
}

TEST(RotationMinimizingFrames, HaveNoTwistOnAPlanarCurve) {
  // A planar curve (random points in a random plane): both reflections have their vectors in the
  // plane, so the plane normal is left exactly invariant. Starting with N = plane normal, N stays
  // the plane normal; starting in the plane, N stays in it (to round-off accumulated over the
  // steps, 1e-12).
  std::mt19937 rng(602);
  const Vec3 e1 = Vec3(1, 2, -0.5).normalized();
  const Vec3 plane_normal = e1.cross(Vec3(0.3, -1, 2)).normalized();
  const Vec3 e2 = plane_normal.cross(e1);
  const int n = 15;
  Points q(n, 3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < n; ++i) q.row(i) = (u(rng) * e1 + u(rng) * e2).transpose();
  const UniformCubicBSpline basis(n);
  const std::vector<double> s = uniformAbscissas(800);
  for (const CurveFrame& f : rotationMinimizingFrames(basis, q, s, plane_normal)) {
    EXPECT_LE((f.normal - plane_normal).norm(), 1e-12);
  }
  for (const CurveFrame& f : rotationMinimizingFrames(basis, q, s, e2)) {
    EXPECT_LE(std::abs(f.normal.dot(plane_normal)), 1e-12);
    EXPECT_LE((f.binormal.cross(plane_normal)).norm(), 1e-12);  // B stays ± the plane normal
  }
}

TEST(RotationMinimizingFrames, ConvergeAtFourthOrderToTheExactFrameOfAHelix) {
  // Helix x(θ) = (a cos θ, a sin θ, b θ), speed c = √(a² + b²), torsion τ = b/c². The exact RMF
  // starting from the Frenet normal is r(θ) = cos φ N + sin φ B with φ' = −τ (arc length), so
  // φ(θ) = −b θ / c. Wang et al. prove O(h⁴) global error: doubling the samples divides the error
  // by ≈ 16 (we accept > 12).
  const double a = 1.0, b = 0.4, c = std::sqrt(a * a + b * b);
  auto exactNormal = [&](double theta) {
    const Vec3 N(-std::cos(theta), -std::sin(theta), 0);                    // Frenet normal
    const Vec3 B = Vec3(b * std::sin(theta), -b * std::cos(theta), a) / c;  // T × N
    const double phi = -b * theta / c;
    return Vec3(std::cos(phi) * N + std::sin(phi) * B);
  };
  double previous = 0.0;
  for (int m : {50, 100, 200, 400}) {
    Points x(m, 3), t(m, 3);
    const double span = 4 * std::numbers::pi;
    for (int k = 0; k < m; ++k) {
      const double theta = span * k / (m - 1);
      x.row(k) << a * std::cos(theta), a * std::sin(theta), b * theta;
      t.row(k) = (Vec3(-a * std::sin(theta), a * std::cos(theta), b) / c).transpose();
    }
    const std::vector<CurveFrame> frames = rotationMinimizingFrames(x, t, exactNormal(0.0));
    double error = 0.0;
    for (int k = 0; k < m; ++k) error = std::max(error, (frames[k].normal - exactNormal(span * k / (m - 1))).norm());
    if (previous > 0.0) {
      EXPECT_GT(previous / error, 12.0) << "m = " << m;
    }
    previous = error;
  }
  EXPECT_LT(previous, 1e-6);
}

TEST(RotationMinimizingFrames, RejectsMismatchedInput) {
  EXPECT_THROW(rotationMinimizingFrames(Points::Zero(3, 3), Points::Zero(2, 3), Vec3::UnitZ()), std::invalid_argument);
  EXPECT_THROW(rotationMinimizingFrames(Points::Zero(2, 3), Points::Zero(2, 3), Vec3::UnitZ()), std::invalid_argument);
  const UniformCubicBSpline basis(5);
  EXPECT_THROW(rotationMinimizingFrames(basis, Points::Zero(5, 3), {0.5, 0.2}, Vec3::UnitZ()), std::invalid_argument);
}

TEST(FrenetFrame, IsOrthonormalWithTheNormalTowardsTheCentreOfCurvature) {
  // T = P'/|P'|, B ∥ P' × P'', N = B × T: orthonormal to round-off (1e-14) and N·P'' > 0.
  std::mt19937 rng(603);
  const int n = 12;
  const UniformCubicBSpline basis(n);
  const Points q = test::randomControlPoints(n, rng);
  for (int k = 0; k <= 100; ++k) {
    const double s = k / 100.0;
    const std::optional<CurveFrame> f = frenetFrame(basis, q, s);
    ASSERT_TRUE(f.has_value());
    expectOrthonormal(*f, 1e-14);
    const CurveDerivatives c = curveDerivatives(basis, q, s);
    EXPECT_GT(f->normal.dot(c.second), 0.0);
    EXPECT_LE(f->binormal.cross(c.first.cross(c.second)).norm(), 1e-12 * c.first.cross(c.second).norm());
  }
}

TEST(FrenetFrame, IsUndefinedOnStraightPartsAndCurvatureMatchesTheBezierEndFormula) {
  // Straight line: P'' ∥ P' → no Frenet frame, curvature 0.
  const UniformCubicBSpline line(6);
  Points q(6, 3);
  for (int i = 0; i < 6; ++i) q.row(i) << i, 2 * i, -i;
  EXPECT_FALSE(frenetFrame(line, q, 0.4).has_value());
  EXPECT_NEAR(curveCurvature(line, q, 0.4), 0.0, 1e-15);
  // Quadratic Bézier (clamped degree 2, 3 points): κ(0) = ½ |Δ0 × Δ1| / |Δ0|³ with Δ_i = q_{i+1} − q_i
  // (Farin, "Curves and Surfaces for CAGD", end-point curvature); exact up to round-off.
  const NonUniformBSpline bezier(2, {0, 0, 0, 1, 1, 1});
  Points b(3, 3);
  b << 0, 0, 0, 1, 0, 0, 1.5, 2, 0;
  const Vec3 d0 = (b.row(1) - b.row(0)).transpose(), d1 = (b.row(2) - b.row(1)).transpose();
  EXPECT_NEAR(curveCurvature(bezier, b, 0.0), 0.5 * d0.cross(d1).norm() / std::pow(d0.norm(), 3), 1e-15);
}

}  // namespace
}  // namespace filum::geometry
