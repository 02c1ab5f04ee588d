#include "filum/collision/segment_closest_points.hpp"

#include <algorithm>

namespace filum::collision {

namespace {
double clamp01(double x) { return std::clamp(x, 0.0, 1.0); }
}  // namespace

double closestParameterOnSegment(const Vec3& a, const Vec3& b, const Vec3& x) {
  const Vec3 d = b - a;
  const double dd = d.squaredNorm();
  return dd > 0.0 ? clamp01((x - a).dot(d) / dd) : 0.0;
}

SegmentClosestPoints closestPointsOnSegments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= 0.0 && e <= 0.0) {
    // Both segments are points.
  } else if (a <= 0.0) {
    t = clamp01(f / e);
  } else {
    const double c = d1.dot(r);
    if (e <= 0.0) {
      s = clamp01(-c / a);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;
      if (denom > 1e-12 * a * e) {
        s = clamp01((b * f - c * e) / denom);
      } else {
        // Parallel: q0 and q1 project on p's line at s = −c/a and (b − c)/a; take the middle of
        // the overlap of that interval with [0, 1] (its nearest end when they do not overlap).
        const double u0 = -c / a, u1 = (b - c) / a;
        const double lo = std::max(0.0, std::min(u0, u1)), hi = std::min(1.0, std::max(u0, u1));
        s = lo <= hi ? 0.5 * (lo + hi) : clamp01(0.5 * (u0 + u1));
      }
      // t at the point of q's line closest to p(s), then s again if t had to be clamped.
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = clamp01(-c / a);
      } else if (t > 1.0) {
        t = 1.0;
        s = clamp01((b - c) / a);
      }
    }
  }
  SegmentClosestPoints out;
  out.s = s;
  out.t = t;
  out.p = p0 + s * d1;
  out.q = q0 + t * d2;
  out.distance = (out.p - out.q).norm();
  return out;
}

}  // namespace filum::collision
