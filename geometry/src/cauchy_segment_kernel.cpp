#include "filum/geometry/cauchy_segment_kernel.hpp"

#include <cmath>
#include <numbers>

namespace filum::geometry {

namespace {

/// Antiderivatives I2, I3 of 1/(p² + s²w²)^n and J3 of w/(p² + s²w²)³ at w.
struct Antiderivatives {
  double i2, i3, j3;
};

Antiderivatives antiderivatives(double w, double p, double s) {
  const double p2 = p * p;
  const double e = p2 + s * s * w * w;                       // p² + s²w²
  const double i1 = std::atan(s * w / p) / (p * s);         // I1
  const double i2 = w / (2.0 * p2 * e) + i1 / (2.0 * p2);   // I2 = w/(2p²e) + I1/(2p²)
  const double i3 = w / (4.0 * p2 * e * e) + 3.0 * i2 / (4.0 * p2);  // I3 = w/(4p²e²) + 3 I2/(4p²)
  const double j3 = -1.0 / (4.0 * s * s * e * e);           // J3 = −1/(4s²e²)
  return {i2, i3, j3};
}

}  // namespace

SegmentField cauchySegmentField(const Vec3& a, const Vec3& b, const Vec3& x, double sharpness) {
  SegmentField out;
  const Vec3 axis = b - a;
  const double length = axis.norm();
  if (!(length > 0.0)) return out;
  const double s = sharpness;
  const Vec3 u = axis / length;
  const Vec3 d = x - a;
  const double t0 = d.dot(u);
  const Vec3 h = d - t0 * u;                               // component ⊥ the segment
  const double p = std::sqrt(1.0 + s * s * h.squaredNorm());  // p² = 1 + s²|h|²
  const Antiderivatives lo = antiderivatives(-t0, p, s), hi = antiderivatives(length - t0, p, s);
  out.value = hi.i2 - lo.i2;
  out.gradient = -4.0 * s * s * ((hi.i3 - lo.i3) * h - (hi.j3 - lo.j3) * u);
  return out;
}

double cauchySegmentIntegral(const Vec3& a, const Vec3& b, const Vec3& x, double sharpness) {
  const Vec3 axis = b - a;
  const double length = axis.norm();
  if (!(length > 0.0)) return 0.0;
  const double s = sharpness;
  const Vec3 u = axis / length;
  const Vec3 d = x - a;
  const double t0 = d.dot(u);
  const double p = std::sqrt(1.0 + s * s * (d - t0 * u).squaredNorm());
  // I2(w) = w/(2p²(p² + s²w²)) + atan(s w/p)/(2p³ s), from w0 = −t0 to w1 = L − t0.
  auto i2 = [&](double w) {
    return w / (2.0 * p * p * (p * p + s * s * w * w)) + std::atan(s * w / p) / (2.0 * p * p * p * s);
  };
  return i2(length - t0) - i2(-t0);
}

double cauchyLineField(double distance, double sharpness) {
  const double e = 1.0 + sharpness * sharpness * distance * distance;
  return std::numbers::pi / (2.0 * sharpness * e * std::sqrt(e));
}

double cauchySegmentMidplaneField(double distance, double segment_length, double sharpness) {
  if (std::isinf(segment_length)) return cauchyLineField(distance, sharpness);
  const double p = std::sqrt(1.0 + sharpness * sharpness * distance * distance);
  return 2.0 * antiderivatives(0.5 * segment_length, p, sharpness).i2;
}

}  // namespace filum::geometry
