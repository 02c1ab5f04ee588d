// Is a thread still knotted? A topological check for knot tying (the knot of knot.json
// must still be a knot after 10 s and after a fast pull): close the open thread far away from
// itself, project it on a plane and compute the knot determinant |Δ(−1)| of the diagram — 1 for
// the unknot, 3 for the trefoil (the overhand knot closed), 5 for the figure-eight knot.
//
// Diagram (Livingston, "Knot Theory", 1993, ch. 3; Fox colourings): project the closed polygon
// along a generic direction d; every crossing of two projected edges has an over strand (the
// higher along d) and an under strand. Cutting the diagram at the n under-crossings gives n arcs
// (arc k ends at under-crossing k and arc k + 1 starts there, in the order along the curve).
// Each crossing gives one row of the colouring matrix,
//   2 x_over − x_in − x_out = 0,
// and the knot determinant is |det| of that n × n matrix with one row and one column deleted
// (the Alexander polynomial at t = −1, an invariant of the knot type; det = 1 for n <= 2). It is
// computed exactly, by elimination modulo two primes near 1e9 (|det| < 5e8 for any knot a
// thread can tie).
//
// Closing: the ends are carried radially away from the curve's centroid to a sphere of radius
// `far` × the curve's extent and joined there through a third point of that sphere, so that the
// closing arc stays far from the knot and cannot be tangled with it.
#pragma once

#include "filum/core/types.hpp"

namespace filum::collision {

/// Closes an open polyline (m >= 2 points) far from itself; returns the closed polygon (its
/// last point is joined to its first).
Points closeFarAway(const Points& open, double far = 100.0);

/// Knot determinant of the closed polygon (last point joined to the first) projected along
/// `direction`; −1 if the projection is not generic (a crossing at a vertex or parallel
/// overlapping edges: choose another direction) or the determinant is out of range. `crossings` (if given) receives n.
long knotDeterminant(const Points& closed, const Vec3& direction, int* crossings = nullptr);

/// The determinant along the first generic one of a fixed list of skew directions
/// (deterministic); −1 if none is generic.
long knotDeterminant(const Points& closed, int* crossings = nullptr);

}  // namespace filum::collision
