// Which knot a thread is tied in: unknot, trefoil (the overhand knot closed), figure-eight,
// granny or square (two overhand knots of the same or of opposite handedness), a surgeon's knot
// (a double throw and a single one), and the throws it is made of — by the Jones
// polynomial of a diagram of the thread closed far away (knot_determinant.hpp: closeFarAway).
// The Alexander polynomial (and the determinant |Δ(−1)|) cannot tell the square knot from the
// granny: both are 3₁ # 3₁ up to mirror, determinant 9; the Jones polynomial can — the square
// knot 3₁ # 3₁* is amphichiral, V(t) = V(1/t), the granny is not.
//
// Method (Kauffman, "State models and the Jones polynomial", Topology 26 (1987) 395):
//   diagram   the closed polygon projected along d; every crossing of two projected edges has an
//             over and an under strand (higher and lower along d) and a sign (+1 when the under
//             strand passes from right to left under the over strand, seen from +d);
//   bracket   ⟨K⟩ = Σ over the 2ⁿ states (an A- or a B-smoothing at each crossing) of
//             A^(#A − #B) δ^(loops − 1), δ = −A² − A⁻², the loops counted by union–find of the 2n
//             arcs between crossing passages; at a crossing whose over strand turns
//             counter-clockwise onto the under strand (o × u > 0), the A-smoothing joins each
//             over end to the under end clockwise of it;
//   Jones     V(t) = (−A³)^(−w) ⟨K⟩ at A = t^(−1/4), w the writhe (the sum of the signs).
// Kinks (a crossing whose two passages follow each other along the curve: Reidemeister I) are
// removed first; of 13 projection directions, the one with the fewest crossings is used.
//
// Throws. A surgeon's throw of k wraps (the thread's two strands wound k times round each other,
// then pulled apart) makes, closed far away, the (2, 2k + 1) torus knot: k = 1 (a single throw,
// the half knot) the trefoil, k = 2 (the double throw of a surgeon's knot) the cinquefoil 5₁.
// Throws tied one on another make their connected sum, whose V is the product of theirs
// (Jones, Ann. Math. 126 (1987) 335, §7 and Thm. 14.1 for V of a torus knot). So V is
// factored into throws of 1 to 3 wraps and either sense (+: the sense whose single throw has
// V = t + t³ − t⁴; −: its mirror, t → 1/t), by exact division; the factoring must be unique.
// The names, besides figure-eight (t⁻² − t⁻¹ + 1 − t + t², no throw) and "other":
//   unknot   no throw                        V = 1
//   trefoil  one single throw                V = t + t³ − t⁴
//   cinquefoil one double throw              V = t² + t⁴ − t⁵ + t⁶ − t⁷
//   septafoil  one triple throw (7₁)
//   square   two single throws, opposite senses (amphichiral: V(t) = V(1/t))
//   granny   two single throws, the same sense
//   surgeon's        a double and a single throw, opposite senses (the surgeon's knot)
//   surgeon's granny a double and a single throw, the same sense
//   "N throws" any other product of N throws (their wraps and senses in `throws`).
// The order of the throws along the thread is not told (a connected sum commutes): `throws` is
// in a canonical order (wraps down, + before −), not the order they were tied in; a double
// throw on a single one reads as a surgeon's knot tied upside down would.
// `mirrored`: the knot is the mirror of the one whose throws, in that order, come first (the
// square knot, its own mirror, never is).
// Cost 2ⁿ · n: up to kMaxKnotCrossings crossings (a tied square knot seen from a good side has 6
// or more, a surgeon's knot 8 or more); beyond, the type is "unknown". knot.csv stops at 16, so
// a knot of three throws (11 or more) may read "unknown" from a poor side.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "filum/core/types.hpp"

namespace filum::collision {

/// A Laurent polynomial in t with integer coefficients: exponent → coefficient (no zeros kept).
using LaurentPolynomial = std::map<int, long>;

struct KnotType {
  std::string name = "unknown";  // see the header: "unknot", "trefoil", ..., "N throws", "other", "unknown"
  int crossings = -1;            // of the diagram used (after removing kinks)
  LaurentPolynomial jones;       // V(t) (empty when unknown)
  /// The throws V factors into: signed wraps (+2 a double throw of sense +), by wraps down and
  /// + before −; empty for the unknot, the figure-eight, "other" and "unknown".
  std::vector<int> throws;
  bool mirrored = false;  // the first throw is of sense − (a left-handed trefoil, granny)
  /// Where the crossings of the diagram used lie along the polygon: each crossing's over and
  /// under passage, as vertex index + fraction of the edge from it (knotSpan reads them).
  std::vector<std::pair<double, double>> crossing_passages;
};

/// The part of an open thread a knot holds: from the first to the last passage of the crossings
/// of the diagram knotType used that are crossings of the thread with itself (both passages
/// before position open_points − 1, where the closing arc starts), as positions on the thread's
/// polyline (vertex index + fraction). Not found for the unknot, an unknown type, or a diagram
/// without such a crossing.
struct KnotSpan {
  bool found = false;
  double first = 0.0, last = 0.0;
};
KnotSpan knotSpan(const KnotType& type, int open_points);

inline constexpr int kMaxKnotCrossings = 22;

/// The knot type of the closed polygon (its last point joined to its first); "unknown" when
/// every projection has more than `max_crossings` crossings after kinks (at most kMaxKnotCrossings).
KnotType knotType(const Points& closed, int max_crossings = kMaxKnotCrossings);

/// The Jones polynomial of the closed polygon's diagram along `direction`; false when the
/// projection is not generic or has more than `max_crossings` crossings (after kinks).
bool jonesPolynomial(const Points& closed, const Vec3& direction, LaurentPolynomial& jones, int* crossings = nullptr,
                     int max_crossings = kMaxKnotCrossings);

/// "t + t^3 - t^4" (for messages and knot.csv).
std::string toString(const LaurentPolynomial& p);

/// "+2 -1" (a surgeon's knot; for knot.csv and metrics).
std::string throwsString(const std::vector<int>& throws);

}  // namespace filum::collision
