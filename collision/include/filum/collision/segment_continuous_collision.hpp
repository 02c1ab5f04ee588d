// Continuous collision detection between two moving segments (edge–edge test of Provot,
// "Collision and self-collision handling in cloth model dedicated to design garments", 1997, and
// Bridson, Fedkiw & Anderson, "Robust treatment of collisions, contact and friction for cloth
// animation", SIGGRAPH 2002): do the centre lines of two pieces of thread pass through each other
// between two steps?
//
// Each endpoint moves linearly over the step, x(τ) = (1 − τ) x_start + τ x_end, τ ∈ [0, 1]. Two
// segments [a0, a1] and [b0, b1] can only meet when their four endpoints are coplanar:
//   f(τ) = (b0 − a0)·((a1 − a0) × (b1 − b0)) = c0 + c1 τ + c2 τ² + c3 τ³ = 0,
// a cubic whose coefficients follow from r = b0 − a0, e = a1 − a0, g = b1 − b0, each linear in τ
// (r = r0 + τ dr, ...):
//   c0 = r0·(e0×g0),  c1 = dr·(e0×g0) + r0·(e0×dg + de×g0),
//   c2 = dr·(e0×dg + de×g0) + r0·(de×dg),  c3 = dr·(de×dg).
// Its roots in [0, 1] are bracketed between the roots of f' (monotone pieces) and refined by
// bisection; at each root, in increasing τ, the segments meet if their distance is below the
// tolerance. When f vanishes identically (motion within one plane) the distance is sampled.
#pragma once

#include <optional>

#include "filum/core/types.hpp"

namespace filum::collision {

struct MovingSegment {
  Vec3 start0, start1;  // endpoints at τ = 0
  Vec3 end0, end1;      // endpoints at τ = 1
};

/// The first τ ∈ [0, 1] at which the two segments are closer than `tolerance` (units of the
/// points) at a coplanarity root, or nullopt if they never meet during the motion.
std::optional<double> firstSegmentContact(const MovingSegment& a, const MovingSegment& b, double tolerance);

/// The signed distance between the lines of two segments, (q − p)·(d1 × d2)/|d1 × d2| for the
/// closest points p, q: its sign flips exactly when one centre line passes through the other
/// (the crossing sign of the pair). Returns 0 for parallel segments.
double signedLineDistance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

}  // namespace filum::collision
