// Splitting a B-spline curve in two, the way a thread is cut ([Lenoir talk 2008]: "multiple insertion at
// the same parametric abscissa decreases the local continuity; local C-1 continuity => cut").
// Inserting u until its multiplicity is d + 1 (Boehm/Oslo, exact) makes the representation
// C−1 at u: with u at knot indices a..a+d, no basis function straddles u, so
//   before: knots t̃_0..t̃_{a+d} (ending with d + 1 copies of u), control points q̃_0..q̃_{a−1},
//   after:  knots t̃_a..t̃_{ñ+d} (starting with d + 1 copies of u), control points q̃_a..q̃_{ñ−1},
// two independent curves with P_before(u) = q̃_{a−1} = q̃_a = P_after(u) = P(u).
// Abscissas: with s* the split abscissa, P(s) = P_before(s/s*) for s <= s* and
// P(s) = P_after((s − s*)/(1 − s*)) for s >= s* (each piece maps its own domain onto [0, 1]).
#pragma once

#include "filum/geometry/bspline_curve.hpp"

namespace filum::geometry {

struct SplitCurve {
  BSplineCurve before;        // covers s ∈ [0, s*]
  BSplineCurve after;         // covers s ∈ [s*, 1]
  double split_abscissa = 0;  // s* (after snapping u onto a nearby existing knot, if any)
  /// The exact refinement A (ñ × n, Oslo): [before.control_points; after.control_points] = A q.
  /// Apply it to velocities (or any per-control-point field) to cut a moving thread:
  /// v_before = (A v).topRows(before.controlPointCount()), v_after = the remaining rows.
  SparseMatrix refinement;
};

/// Split at abscissa s ∈ (0, 1) (std::invalid_argument otherwise). u(s) within 8 ulps of the
/// domain width from an existing knot is snapped onto it, so that no sliver piece is created.
SplitCurve splitCurve(const BSplineCurve& curve, double s);

/// Split at the knot parameter u ∈ (t_d, t_n).
SplitCurve splitCurveAtParameter(const BSplineCurve& curve, double u);

}  // namespace filum::geometry
