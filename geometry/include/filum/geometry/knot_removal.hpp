// Knot removal (the inverse of Boehm insertion; Tiller 1992, Piegl & Tiller §5.4) with a
// guaranteed error bound. Removal is in general an approximation ([Lenoir talk 2008]: "simplification is
// often an approximation"): the curve on the coarser knots τ = t \ {u} can only reproduce P if
// P is one order smoother at u than its knot multiplicity allows.
//
// Method. Inserting u back into τ is exact and linear: q = A p (Boehm, knot_insertion.hpp), with
// A the identity above row k − d, the bidiagonal rows q_i = α_i p_i + (1 − α_i) p_{i−1},
// α_i = (u − τ_i)/(τ_{i+d} − τ_i) for k − d + 1 <= i <= k, and a shift below. We keep
// p_{k−d} = q_{k−d} and p_k = q_{k+1} (so the curve is unchanged outside the d + 1 spans around
// u) and choose the d − 1 points p_{k−d+1}..p_{k−1} by least squares on the d bidiagonal rows.
// Error bound: P_old(u) − P_new(u) = Σ_i B_i(u) (q_i − (A p)_i) on the original knots, and the
// B_i are non-negative with Σ B_i = 1 in the domain, hence
//   max_s |P_old(s) − P_new(s)| <= max_i |q_i − (A p)_i|     (convex-hull property).
#pragma once

#include "filum/geometry/bspline_curve.hpp"

namespace filum::geometry {

struct KnotRemoval {
  BSplineCurve curve;         // the curve with fewer knots (one less control point per removal)
  double error_bound = 0.0;   // max_s |P_original(s) − P_new(s)| <= error_bound (units of q)
  int removed = 0;            // how many knots were removed
};

/// Removes one occurrence of the knot u, which must be a knot strictly inside (t_d, t_n)
/// (std::invalid_argument otherwise). Always succeeds; the returned bound says at what cost
/// (round-off level when the knot was removable exactly, e.g. just inserted).
KnotRemoval removeKnot(const BSplineCurve& curve, double u);

/// Greedy simplification: repeatedly removes the interior knot whose removal has the smallest
/// bound while the accumulated bound (sum of the individual bounds, triangle inequality) stays
/// <= tolerance (>= 0, units of q).
KnotRemoval simplifyCurve(const BSplineCurve& curve, double tolerance);

}  // namespace filum::geometry
