// Exact knot insertion: a B-spline curve on knots t is rewritten on a refined knot vector
// t̃ ⊃ t without changing P(s) ([Lenoir talk 2008], "adaptive resolution of the geometry":
// more control points where the knot is tied).
//
// Boehm (1980), one knot u with t_k <= u < t_{k+1}:
//   q̃_i = q_i                                  for i <= k − d,
//   q̃_i = α_i q_i + (1 − α_i) q_{i−1},  α_i = (u − t_i)/(t_{i+d} − t_i),   k − d + 1 <= i <= k,
//   q̃_i = q_{i−1}                              for i >= k + 1.
//
// Oslo algorithm (Cohen, Lyche & Riesenfeld 1980), any number of knots at once, with the
// discrete B-splines α of [Lenoir talk 2008]:  B_i(u) = Σ_j α^d_{i,j} B̃_j(u),  q̃_j = Σ_i α^d_{i,j} q_i,
//   α^0_{i,j} = 1 if t_i <= t̃_j < t_{i+1}, else 0,
//   α^r_{i,j} = (t̃_{j+r} − t_i)/(t_{i+r} − t_i) α^{r−1}_{i,j} + (t_{i+r+1} − t̃_{j+r})/(t_{i+r+1} − t_{i+1}) α^{r−1}_{i+1,j}
// (Cox–de Boor with the evaluation point moving to t̃_{j+r} at level r). Only the d + 1 values
// i = μ−d..μ are non-zero, μ the coarse span of t̃_j: O(d²) per new control point. On an
// unclamped vector, t̃_j may lie left of the domain (μ < d): the terms i < 0 have no B-spline and
// are skipped (the others never depend on them). Every factor is >= 0, so A is non-negative.
//
// Inserted knots must lie strictly inside the domain (t_d, t_n) and no knot may end up with
// multiplicity above d + 1; the domain, hence the map s ↦ u, is unchanged.
#pragma once

#include <vector>

#include "filum/core/types.hpp"
#include "filum/geometry/bspline_curve.hpp"

namespace filum::geometry {

/// Boehm's algorithm: u inserted `times` times (>= 1), one at a time. Throws
/// std::invalid_argument if u is not strictly inside (t_d, t_n) or its multiplicity would exceed d + 1.
BSplineCurve insertKnot(const BSplineCurve& curve, double u, int times = 1);

/// Oslo algorithm: all `new_knots` inserted at once (any order, repeats allowed). Same
/// preconditions as insertKnot for each knot. O((n + k) d²) for k new knots.
BSplineCurve insertKnots(const BSplineCurve& curve, const std::vector<double>& new_knots);

/// The sorted union t̃ = t ∪ new_knots (multiplicities add); validates as insertKnots does.
std::vector<double> refinedKnotVector(int degree, const std::vector<double>& knots,
                                      const std::vector<double>& new_knots);

/// The Oslo refinement matrix A (ñ × n, ≤ d + 1 entries per row, rows sum to 1): q̃ = A q.
/// The same matrix maps velocities and any other per-control-point field of a dynamic spline.
/// `refined_knots` must be a refinement of `knots` as produced by refinedKnotVector.
SparseMatrix knotInsertionMatrix(int degree, const std::vector<double>& knots,
                                 const std::vector<double>& refined_knots);

}  // namespace filum::geometry
