// The Cauchy kernel of convolution surfaces and its closed-form integral along a segment
// (J. McCormack, A. Sherstyuk, "Creating and rendering convolution surfaces", Computer Graphics
// Forum 17(2), 1998, §3 and appendix):
//   k(r) = 1/(1 + s² r²)²,   s > 0 the sharpness (1/units of length).
// For the segment c(t) = a + t u, t ∈ [0, L], u = (b − a)/L, and a point x with d = x − a,
// t0 = d·u, h = d − t0 u (h ⊥ u), p² = 1 + s²|h|², w = t − t0 (w0 = −t0, w1 = L − t0):
//   F(x) = ∫_0^L k(|x − c(t)|) dt = ∫_{w0}^{w1} dw/(p² + s²w²)² = I2(w1) − I2(w0),
// with the antiderivatives I_n(w) of 1/(p² + s²w²)^n,
//   I1(w) = atan(s w/p)/(p s),
//   I_{n+1}(w) = w/(2n p² (p² + s²w²)^n) + (2n − 1)/(2n p²) I_n(w)          (reduction formula).
// Gradient: ∇_x k = −4 s² (x − c)/(1 + s²r²)³ and x − c(t) = h − w u, hence
//   ∇F(x) = −4 s² [ h (I3(w1) − I3(w0)) − u (J3(w1) − J3(w0)) ],  J3(w) = −1/(4 s² (p² + s²w²)²).
// An infinite line at distance r gives F∞(r) = π/(2 s (1 + s²r²)^{3/2}).
#pragma once

#include "filum/core/types.hpp"

namespace filum::geometry {

/// The kernel k(r) = 1/(1 + s² r²)².
inline double cauchyKernel(double r, double sharpness) {
  const double e = 1.0 + sharpness * sharpness * r * r;
  return 1.0 / (e * e);
}

struct SegmentField {
  double value = 0.0;              // F(x) (units of length: ∫ dt of a dimensionless kernel)
  Vec3 gradient = Vec3::Zero();    // ∇F(x)
};

/// F and ∇F at x for the segment [a, b]; a zero-length segment contributes nothing.
/// Precondition: sharpness > 0.
SegmentField cauchySegmentField(const Vec3& a, const Vec3& b, const Vec3& x, double sharpness);

/// F(x) only (cheaper: no I3, J3).
double cauchySegmentIntegral(const Vec3& a, const Vec3& b, const Vec3& x, double sharpness);

/// F∞(r) = π / (2 s (1 + s² r²)^{3/2}): the field of an infinite straight line at distance r.
double cauchyLineField(double distance, double sharpness);

/// F at distance r from the midpoint of a segment of length L, perpendicular to it:
/// 2 I2(L/2) (I2 with p² = 1 + s²r²); L = +infinity gives cauchyLineField.
double cauchySegmentMidplaneField(double distance, double segment_length, double sharpness);

}  // namespace filum::geometry
