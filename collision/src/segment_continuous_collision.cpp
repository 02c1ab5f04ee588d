#include "filum/collision/segment_continuous_collision.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>

#include "filum/collision/segment_closest_points.hpp"

namespace filum::collision {

namespace {

struct Cubic {
  double c0, c1, c2, c3;
  double operator()(double t) const { return ((c3 * t + c2) * t + c1) * t + c0; }
};

/// Roots of f on [lo, hi] where f is monotone: one or none, by bisection to round-off.
std::optional<double> monotoneRoot(const Cubic& f, double lo, double hi) {
  double flo = f(lo), fhi = f(hi);
  if (flo == 0.0) return lo;
  if (fhi == 0.0) return hi;
  if ((flo < 0.0) == (fhi < 0.0)) return std::nullopt;
  for (int k = 0; k < 80 && hi - lo > 1e-15; ++k) {
    const double mid = 0.5 * (lo + hi);
    const double fm = f(mid);
    if (fm == 0.0) return mid;
    if ((fm < 0.0) == (flo < 0.0)) {
      lo = mid;
      flo = fm;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

Vec3 lerp(const Vec3& a, const Vec3& b, double t) { return a + t * (b - a); }

double distanceAt(const MovingSegment& a, const MovingSegment& b, double tau) {
  return closestPointsOnSegments(lerp(a.start0, a.end0, tau), lerp(a.start1, a.end1, tau),
                                 lerp(b.start0, b.end0, tau), lerp(b.start1, b.end1, tau))
      .distance;
}

}  // namespace

std::optional<double> firstSegmentContact(const MovingSegment& a, const MovingSegment& b, double tolerance) {
  // Coplanarity cubic f(τ) = r·(e × g) (see the header).
  const Vec3 r0 = b.start0 - a.start0, dr = (b.end0 - a.end0) - r0;
  const Vec3 e0 = a.start1 - a.start0, de = (a.end1 - a.end0) - e0;
  const Vec3 g0 = b.start1 - b.start0, dg = (b.end1 - b.end0) - g0;
  const Vec3 eg0 = e0.cross(g0), eg1 = e0.cross(dg) + de.cross(g0), eg2 = de.cross(dg);
  const Cubic f{r0.dot(eg0), dr.dot(eg0) + r0.dot(eg1), dr.dot(eg1) + r0.dot(eg2), dr.dot(eg2)};

  // Scale of f: |r| |e| |g| over the motion; below 1e-14 of it f is round-off (coplanar motion).
  const double scale = (r0.norm() + dr.norm()) * (e0.norm() + de.norm()) * (g0.norm() + dg.norm());
  const double size = std::abs(f.c0) + std::abs(f.c1) + std::abs(f.c2) + std::abs(f.c3);
  if (!(size > 1e-14 * scale)) {
    // Degenerate: the endpoints stay coplanar; sample the distance (64 sub-steps).
    for (int k = 0; k <= 64; ++k)
      if (distanceAt(a, b, k / 64.0) <= tolerance) return k / 64.0;
    return std::nullopt;
  }

  // Monotone pieces of f on [0, 1]: split at the roots of f'(τ) = c1 + 2 c2 τ + 3 c3 τ².
  std::array<double, 4> cuts{0.0, 1.0, 1.0, 1.0};
  int count = 1;
  const double qa = 3.0 * f.c3, qb = 2.0 * f.c2, qc = f.c1;
  auto addCut = [&](double t) {
    if (t > 0.0 && t < 1.0) cuts[count++] = t;
  };
  if (qa != 0.0) {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double sq = std::sqrt(disc);
      // Numerically stable roots of the quadratic.
      const double qq = -0.5 * (qb + (qb >= 0.0 ? sq : -sq));
      addCut(qq / qa);
      if (qq != 0.0) addCut(qc / qq);
    }
  } else if (qb != 0.0) {
    addCut(-qc / qb);
  }
  cuts[count++] = 1.0;
  // Insertion sort of the (at most 4) cuts.
  for (int i = 1; i < count; ++i)
    for (int j = i; j > 0 && cuts[j] < cuts[j - 1]; --j) std::swap(cuts[j], cuts[j - 1]);

  for (int k = 0; k + 1 < count; ++k) {
    const std::optional<double> root = monotoneRoot(f, cuts[k], cuts[k + 1]);
    if (root && distanceAt(a, b, *root) <= tolerance) return root;
  }
  return std::nullopt;
}

double signedLineDistance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 n = (p1 - p0).cross(q1 - q0);
  const double norm = n.norm();
  if (!(norm > 0.0)) return 0.0;
  const SegmentClosestPoints c = closestPointsOnSegments(p0, p1, q0, q1);
  return (c.q - c.p).dot(n) / norm;
}

}  // namespace filum::collision
