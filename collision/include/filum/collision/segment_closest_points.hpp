// Closest points of two segments [p0, p1] and [q0, q1]: the contact geometry between two pieces
// of the sphere chains sampled on threads (the swept union of the spheres of radius r between two
// consecutive centres is a capsule of radius r around the segment).
//
// Minimise |p(s) − q(t)|², p(s) = p0 + s d1, q(t) = q0 + t d2, s, t ∈ [0, 1] (Ericson, Real-Time
// Collision Detection, 2005, §5.1.9): with r = p0 − q0, a = d1·d1, b = d1·d2, e = d2·d2,
// c = d1·r, f = d2·r the unconstrained minimum solves
//   [a −b; −b e] [s; t] = [−c; f]  →  s = (b f − c e)/(a e − b²),  t = (b s + f)/e,
// clamped to the square, s recomputed after t is clamped. Parallel segments (a e − b² <=
// 1e-12 a e) have a line of minima: s is taken at the middle of the overlap of the two
// segments (so that two threads lying side by side get one contact per segment pair, spread
// along them, and not all at the first endpoint).
#pragma once

#include "filum/core/types.hpp"

namespace filum::collision {

struct SegmentClosestPoints {
  double s = 0.0;         // parameter on [p0, p1], in [0, 1]
  double t = 0.0;         // parameter on [q0, q1], in [0, 1]
  Vec3 p;                 // p0 + s (p1 − p0)
  Vec3 q;                 // q0 + t (q1 − q0)
  double distance = 0.0;  // |p − q| (units of the points)
};

SegmentClosestPoints closestPointsOnSegments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

/// Closest point of segment [a, b] to x: parameter t ∈ [0, 1] of a + t (b − a).
double closestParameterOnSegment(const Vec3& a, const Vec3& b, const Vec3& x);

}  // namespace filum::collision
