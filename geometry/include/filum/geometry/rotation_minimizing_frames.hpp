// Rotation-minimizing frames (RMF) by the double reflection method: W. Wang, B. Jüttler,
// D. Zheng, Y. Liu, "Computation of rotation minimizing frames", ACM TOG 27(1), 2008, §4,
// Algorithm 1. An RMF has no angular velocity about the tangent (r' ∥ T): no artificial twist,
// unlike the Frenet frame, and it is defined at inflections and on straight parts.
// From frame (x_i, t_i, r_i) to x_{i+1}, t_{i+1}:
//   v1 = x_{i+1} − x_i,  c1 = v1·v1,
//   r_i^L = r_i − (2/c1)(v1·r_i) v1,  t_i^L = t_i − (2/c1)(v1·t_i) v1      (reflection R1),
//   v2 = t_{i+1} − t_i^L,  c2 = v2·v2,
//   r_{i+1} = r_i^L − (2/c2)(v2·r_i^L) v2,  s_{i+1} = t_{i+1} × r_{i+1}       (reflection R2).
// Global error O(h⁴) in the sample spacing h (Wang et al. §4.2). A reflection is skipped when
// its vector is zero (c = 0: coincident points, or tangents already matching). We re-project r
// onto the plane ⊥ t_{i+1} and renormalise after each step (a change at round-off level that
// keeps the frames orthonormal to ~1e-15 over any number of steps).
#pragma once

#include <vector>

#include "filum/core/types.hpp"
#include "filum/geometry/curve_frame.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::geometry {

/// Frames along sampled points x_i (m × 3) with unit tangents t_i (m × 3), m >= 1; the first
/// normal is initial_normal projected onto the plane ⊥ t_0 and normalised (any perpendicular
/// when it is parallel to t_0). Throws std::invalid_argument on mismatched sizes or a tangent
/// that is not unit to 1e-8.
std::vector<CurveFrame> rotationMinimizingFrames(ConstPointsRef points, ConstPointsRef unit_tangents,
                                                 const Vec3& initial_normal);

/// Frames of the curve (basis, q) at the given abscissas (non-decreasing, in [0, 1]); the
/// tangent is P'(s)/|P'(s)| (the previous tangent where P'(s) = 0).
std::vector<CurveFrame> rotationMinimizingFrames(const CurveBasis& basis, ConstPointsRef q,
                                                 const std::vector<double>& abscissas, const Vec3& initial_normal);

/// A unit vector perpendicular to the unit vector t (deterministic choice).
Vec3 anyPerpendicular(const Vec3& t);

}  // namespace filum::geometry
