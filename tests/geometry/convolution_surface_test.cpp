// Convolution surfaces with the Cauchy kernel: closed form against quadrature, gradient against
// finite differences, additivity, iso-value from a radius.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

#include "filum/geometry/convolution_surface.hpp"
#include "filum/geometry/gauss_legendre.hpp"
#include "filum/geometry/uniform_cubic_bspline.hpp"

namespace filum::geometry {
namespace {

/// ∫_0^L k(|x − c(t)|) dt and ∫ ∇_x k by composite 16-point Gauss-Legendre on 64 pieces. The
/// integrand is analytic with a length scale >= min(1/s, distance to the segment); with pieces of
/// length <= 1/64 of a segment of length <= 3 and s <= 4 its relative error is < 1e-15.
SegmentField numericalSegmentField(const Vec3& a, const Vec3& b, const Vec3& x, double s) {
  static const QuadratureRule rule = gaussLegendre(16);
  SegmentField out;
  const double length = (b - a).norm();
  const int pieces = 64;
  for (int p = 0; p < pieces; ++p) {
    const double t0 = length * p / pieces, t1 = length * (p + 1) / pieces;
    for (std::size_t g = 0; g < rule.nodes.size(); ++g) {
      const double t = 0.5 * (t0 + t1) + 0.5 * (t1 - t0) * rule.nodes[g];
      const double w = 0.5 * (t1 - t0) * rule.weights[g];
      const Vec3 r = x - (a + (b - a) * (t / length));
      const double e = 1.0 + s * s * r.squaredNorm();
      out.value += w / (e * e);
      out.gradient += w * (-4.0 * s * s / (e * e * e)) * r;  // ∇k = −4 s² r / (1 + s²r²)³
    }
  }
  return out;
}

TEST(CauchySegmentKernel, ClosedFormMatchesQuadratureOfTheKernel) {
  // Points near and far, beside, beyond the ends and on the axis. The closed form involves a few
  // cancelling atan/rational terms of size <= F∞(0) = π/(2s): relative 1e-12 of max(F, 1e-3 π/2s)
  // covers their round-off.
  std::mt19937 rng(701);
  std::uniform_real_distribution<double> u(-2, 2);
  for (double s : {0.5, 1.0, 4.0}) {
    for (int k = 0; k < 200; ++k) {
      const Vec3 a(u(rng), u(rng), u(rng));
      const Vec3 b = a + Vec3(u(rng), u(rng), u(rng)).normalized() * (0.1 + std::abs(u(rng)));
      Vec3 x(u(rng), u(rng), u(rng));
      if (k % 10 == 0) x = a + 1.7 * (b - a);  // on the axis, beyond b
      if (k % 10 == 1) x = 0.3 * a + 0.7 * b;  // on the segment
      const SegmentField exact = cauchySegmentField(a, b, x, s);
      const SegmentField numeric = numericalSegmentField(a, b, x, s);
      const double scale = std::max(numeric.value, 1e-3 * std::numbers::pi / (2 * s));
      EXPECT_NEAR(exact.value, numeric.value, 1e-12 * scale) << "s = " << s << " k = " << k;
      // Value-only route: the same I2 difference in another order; the I2 terms are <= π/(4s), so
      // round-off is a few ε of π/(2s).
      EXPECT_NEAR(cauchySegmentIntegral(a, b, x, s), exact.value, 8 * std::numeric_limits<double>::epsilon() * std::numbers::pi / (2 * s));
      EXPECT_LE((exact.gradient - numeric.gradient).norm(), 1e-12 * std::max(numeric.gradient.norm(), s * scale))
          << "s = " << s << " k = " << k;
    }
  }
}

TEST(CauchySegmentKernel, GradientMatchesCentralFiniteDifferences) {
  // Central differences with h = 1e-5: truncation h²/6 |F'''| (|F'''| <= ~10 s³ F∞(0) for these
  // sharpness values) plus round-off ε F / h; 1e-8 relative to the field scale covers both.
  std::mt19937 rng(702);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  const double h = 1e-5, s = 2.0;
  const Vec3 a(0.1, -0.2, 0.3), b(0.9, 0.5, -0.4);
  for (int k = 0; k < 100; ++k) {
    const Vec3 x(u(rng), u(rng), u(rng));
    const Vec3 g = cauchySegmentField(a, b, x, s).gradient;
    Vec3 fd;
    for (int c = 0; c < 3; ++c) {
      const Vec3 e = h * Vec3::Unit(c);
      fd[c] = (cauchySegmentField(a, b, x + e, s).value - cauchySegmentField(a, b, x - e, s).value) / (2 * h);
    }
    EXPECT_LE((g - fd).norm(), 1e-8 * std::numbers::pi / (2 * s));
  }
}

TEST(CauchySegmentKernel, LongSegmentTendsToTheInfiniteLineField) {
  // The two missing tails beyond ±L/2 contribute 2∫_{L/2}^∞ dw/(p² + s²w²)² < 2/(3 s⁴ (L/2)³):
  // with s = 1, L = 2e3 that is 6.7e-10; and the midplane helper agrees with the general formula.
  const double s = 1.0, L = 2000.0;
  for (double r : {0.0, 0.5, 1.0, 3.0}) {
    const double line = cauchyLineField(r, s);
    EXPECT_NEAR(cauchySegmentMidplaneField(r, L, s), line, 2.0 / (3 * std::pow(L / 2, 3)));
    EXPECT_NEAR(cauchySegmentMidplaneField(r, std::numeric_limits<double>::infinity(), s), line, 0.0);
    const SegmentField f = cauchySegmentField(Vec3(-L / 2, 0, 0), Vec3(L / 2, 0, 0), Vec3(0, r, 0), s);
    EXPECT_NEAR(f.value, cauchySegmentMidplaneField(r, L, s), 1e-14);
  }
}

TEST(ConvolutionSurface, SplittingTheSkeletonLeavesTheFieldUnchanged) {
  // The field is a line integral: a segment cut into 7 collinear pieces gives the same F and ∇F
  // (round-off of 7 closed forms: 1e-13 relative to the field scale π/(2s)).
  ConvolutionSurface whole(0.2), pieces(0.2);
  const Vec3 a(0, 0, 0), b(1, 0.5, 0.2);
  whole.addSegment(a, b);
  Points polyline(8, 3);
  for (int i = 0; i < 8; ++i) polyline.row(i) = (a + (b - a) * (i / 7.0)).transpose();
  pieces.addPolyline(polyline);
  EXPECT_EQ(pieces.segmentCount(), 7);
  const double scale = std::numbers::pi / (2 * whole.sharpness());
  std::mt19937 rng(703);
  std::uniform_real_distribution<double> u(-0.5, 1.5);
  for (int k = 0; k < 100; ++k) {
    const Vec3 x(u(rng), u(rng), u(rng));
    EXPECT_NEAR(whole.field(x), pieces.field(x), 1e-13 * scale);
    EXPECT_LE((whole.fieldGradient(x) - pieces.fieldGradient(x)).norm(), 1e-13 * scale * whole.sharpness());
  }
}

TEST(ConvolutionSurface, IsoValueGivesTheRequestedRadius) {
  // Single segment of length L with the iso-value set for that length: the midplane point at
  // distance R is on the surface (two routes to the same closed form: 1e-15 relative).
  const double R = 0.05;
  const ConvolutionSurface segment(R, 0.0, 0.4);
  ConvolutionSurface single = segment;
  single.addSegment(Vec3(0, 0, 0), Vec3(0.4, 0, 0));
  EXPECT_NEAR(single.implicitValue(Vec3(0.2, 0, R)), 0.0, 1e-15 * single.isoValue());
  EXPECT_LT(single.implicitValue(Vec3(0.2, 0, 0.5 * R)), 0.0);  // inside
  EXPECT_GT(single.implicitValue(Vec3(0.2, 0, 2 * R)), 0.0);    // outside
  // A long straight polyline (100 R, 50 segments) with the default (infinite line) iso-value: the
  // surface crosses the midplane at R up to the missing tails, δF < 2 R/(3·50³) → δR =
  // δF/|dF/dr| < 7e-6 R; found by bisection on f along a perpendicular ray (to 1e-12 R).
  ConvolutionSurface tube(R);
  Points line(51, 3);
  for (int i = 0; i <= 50; ++i) line.row(i) << 100 * R * i / 50.0, 0, 0;
  tube.addPolyline(line);
  const Vec3 centre(50 * R, 0, 0), ray = Vec3(0, 1, 1).normalized();
  double lo = 0.0, hi = 3 * R;
  while (hi - lo > 1e-12 * R) {
    const double mid = 0.5 * (lo + hi);
    (tube.implicitValue(centre + mid * ray) < 0.0 ? lo : hi) = mid;
  }
  EXPECT_NEAR(lo, R, 1e-5 * R);
  // The implicit gradient −∇F points outwards (away from the axis) on the surface.
  const Vec3 on_surface = centre + lo * ray;
  EXPECT_GT((-tube.fieldGradient(on_surface)).dot(ray), 0.0);
}

TEST(ConvolutionSurface, CurveSkeletonOfAStraightSplineIsOneSegment) {
  // A uniform cubic B-spline on collinear equally spaced points is the straight segment from q_1
  // to q_{n−2}; addCurve samples it as chords of that same segment, so the fields agree to the
  // arc-length accuracy of the sample positions (1e-10 relative) times |∇F|: 1e-9 relative.
  const int n = 8;
  const UniformCubicBSpline basis(n);
  Points q(n, 3);
  for (int i = 0; i < n; ++i) q.row(i) << 0.1 * i, 0.05 * i, 0;
  ConvolutionSurface from_curve(0.03), segment(0.03);
  from_curve.addCurve(basis, q, 20);
  EXPECT_EQ(from_curve.segmentCount(), 20);
  segment.addSegment(q.row(1).transpose(), q.row(n - 2).transpose());
  const double scale = std::numbers::pi / (2 * segment.sharpness());
  for (const Vec3& x : {Vec3(0.3, 0.1, 0.02), Vec3(0.0, 0.0, 0.1), Vec3(0.7, 0.4, -0.05)})
    EXPECT_NEAR(from_curve.field(x), segment.field(x), 1e-9 * scale);
}

TEST(ConvolutionSurface, RejectsBadParameters) {
  EXPECT_THROW(ConvolutionSurface(0.0), std::invalid_argument);
  EXPECT_THROW(ConvolutionSurface(-1.0), std::invalid_argument);
  EXPECT_THROW(ConvolutionSurface(1.0, -2.0), std::invalid_argument);
  EXPECT_THROW(ConvolutionSurface(1.0, 1.0, 0.0), std::invalid_argument);
  ConvolutionSurface s(1.0);
  EXPECT_THROW(s.addPolyline(Points::Zero(1, 3)), std::invalid_argument);
  // A zero-length segment contributes nothing.
  s.addSegment(Vec3::Zero(), Vec3::Zero());
  EXPECT_EQ(s.field(Vec3(0.1, 0, 0)), 0.0);
}

/// The radius at which the surface crosses the perpendicular to the x axis through (x, 0, 0):
/// f = T − F rises with the distance d from a straight tube's axis; bisection on [lo, hi].
double surfaceRadius(const ConvolutionSurface& surface, double x, double lo, double hi) {
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (surface.implicitValue(Vec3(x, mid, 0.0)) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(ConvolutionSurface, AWeightedTubeTakesTheRadiusOfItsWeight) {
  // Reference: the field of an infinite straight line, F∞(d) = π / (2 s (1 + s²d²)^{3/2}), the
  // closed form of ∫ dt / (1 + s²(d² + t²))² written here.
  const double R = 1e-3, r = 0.4e-3, s = 1.0 / R;
  auto line = [s](double d) { return std::numbers::pi / (2.0 * s * std::pow(1.0 + s * s * d * d, 1.5)); };
  // |dF∞/dd| = 3π s d / (2 (1 + s²d²)^{5/2}).
  auto slope = [s](double d) { return 3.0 * std::numbers::pi * s * d / (2.0 * std::pow(1.0 + s * s * d * d, 2.5)); };
  ConvolutionSurface surface(R);
  const double w_shaft = surface.weightForRadius(R), w_tip = surface.weightForRadius(r);
  // w F∞(r) = T to a few roundings (a quotient and a product of closed forms).
  EXPECT_NEAR(w_tip * line(r), surface.isoValue(), 8 * std::numeric_limits<double>::epsilon() * surface.isoValue());
  EXPECT_NEAR(w_shaft, 1.0, 8 * std::numeric_limits<double>::epsilon());
  EXPECT_THROW(surface.weightForRadius(0.0), std::invalid_argument);
  EXPECT_THROW(surface.addSegment(Vec3::Zero(), Vec3::UnitX(), -1.0), std::invalid_argument);

  // A shaft on x ∈ [−H, 0] and a thin tip on [0, H], H = 40/s, each as 40 segments (the field is
  // additive). At the middle of either half the field is the infinite tube's of that half's weight
  // w_i, but for the kernel beyond H/2 on either side: its own far end misses w_i ∫_{H/2}^∞ k, the
  // other half puts w_j ∫_{H/2}^{3H/2} k for w_i ∫_{H/2}^∞ k, so |ΔF| <= (2 w_i + w_j) ∫_{H/2}^∞ k
  // with ∫_D^∞ dt / (1 + s²(d² + t²))² <= ∫_D^∞ dt / (s t)⁴ = 1 / (3 s⁴ D³). The radius then errs by
  // |ΔF| / (w_i |dF∞/dd|), twice that allowing for the slope's change over the interval.
  const double H = 40.0 / s, tail = 1.0 / (3.0 * std::pow(s, 4) * std::pow(0.5 * H, 3));
  for (int k = 0; k < 40; ++k) {
    surface.addSegment(Vec3(-H + H * k / 40, 0, 0), Vec3(-H + H * (k + 1) / 40, 0, 0), w_shaft);
    surface.addSegment(Vec3(H * k / 40, 0, 0), Vec3(H * (k + 1) / 40, 0, 0), w_tip);
  }
  const double shaft_error = 2.0 * (2.0 * w_shaft + w_tip) * tail / (w_shaft * slope(R));
  const double tip_error = 2.0 * (2.0 * w_tip + w_shaft) * tail / (w_tip * slope(r));
  EXPECT_NEAR(surfaceRadius(surface, -0.5 * H, 0.1 * R, 3.0 * R), R, shaft_error);
  EXPECT_NEAR(surfaceRadius(surface, 0.5 * H, 0.1 * R, 3.0 * R), r, tip_error);
  EXPECT_LT(tip_error, 1e-3 * r);  // the bound tells the two sections apart by far
}

}  // namespace
}  // namespace filum::geometry
