// Closest point of a spline curve to a point x: s* = argmin_{s ∈ [0,1]} |P(s) − x|².
//
// Global search, then Newton (Piegl & Tiller §6.1, point inversion): each polynomial piece of the
// basis is sampled at `samples_per_piece` + 1 abscissas (if continuity() < 0, inner piece ends
// 1e-12 inside the piece, so that both one-sided limits are seen where a knot of multiplicity
// d + 1 breaks the curve; the answer there is within |P'| 1e-12 of the limit point);
// every discrete local minimum s_k of the distance (piece ends included) is refined by Newton on
//   g(s) = (P(s) − x)·P'(s) = 0,   g'(s) = |P'(s)|² + (P(s) − x)·P''(s),
// in the half-brackets [s_{k−1}, s_k] and [s_k, s_{k+1}] where g goes from − to + (a minimum),
// safeguarded by bisection on the sign of g. The samples themselves stay candidates, so the
// result is clamped to [0, 1] and to the closed pieces. The best candidate over the whole curve
// wins. The sampling must be fine enough that two minima of the distance are not within one
// sample step of each other (8 samples per piece resolve features down to about 1/8 of a piece;
// raise it for tightly folded curves).
#pragma once

#include "filum/core/types.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::geometry {

struct ClosestPoint {
  double s = 0.0;         // abscissa in [0, 1]
  Vec3 point;             // P(s)
  double distance = 0.0;  // |P(s) − x| (units of q)
};

/// Closest point of the curve (basis, q) to x. samples_per_piece >= 1; q has
/// basis.controlPointCount() rows (std::invalid_argument otherwise).
ClosestPoint closestPoint(const CurveBasis& basis, ConstPointsRef q, const Vec3& x, int samples_per_piece = 8);

}  // namespace filum::geometry
