// A B-spline curve in knot form, P(u) = Σ_i B_{i,d}(u) q_i (de Boor; Piegl & Tiller ch. 2-3):
// degree, knot vector and control points together, the representation that knot insertion
// (Boehm, Oslo), knot removal and splitting work on. Any basis of the CurveBasis interface can
// be converted to it exactly:
//  - uniform cubic B-spline: the same control points on the uniform knots t_i = i − 3;
//  - Catmull-Rom: each segment is a cubic Bézier curve with inner points
//      b1 = q_{j+1} + (q_{j+2} − q_j)/6,  b2 = q_{j+2} − (q_{j+3} − q_{j+1})/6
//    (Hermite → Bézier, tangents (q_{j+2} − q_j)/2), joined C1: interior knots of multiplicity
//    2 = d − 1 on a clamped vector, control points q_1, b1_0, b2_0, b1_1, ..., b2_{N−1}, q_{n−2};
//  - NUBS: its own knots.
// The abscissa s ∈ [0, 1] is preserved (same affine map onto the domain).
#pragma once

#include <vector>

#include "filum/core/types.hpp"
#include "filum/geometry/nonuniform_bspline.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::geometry {

struct BSplineCurve {
  int degree = 3;
  std::vector<double> knots;  // t_0..t_{n+d}, non-decreasing (validateKnotVector)
  Points control_points;      // q (n × 3)

  int controlPointCount() const { return static_cast<int>(control_points.rows()); }
  /// The basis on these knots (validates them; throws std::invalid_argument).
  NonUniformBSpline basis() const { return NonUniformBSpline(degree, knots); }
};

/// Throws std::invalid_argument if the knots are not a valid degree-d knot vector for
/// curve.control_points.rows() control points.
void validateBSplineCurve(const BSplineCurve& curve, const char* what);

/// The same curve (same P(s) for every s ∈ [0, 1]) in knot form. Supports UniformCubicBSpline,
/// CatmullRomSpline and NonUniformBSpline; q has basis.controlPointCount() rows. Throws
/// std::invalid_argument for another basis or a wrong number of control points.
BSplineCurve toBSplineCurve(const CurveBasis& basis, ConstPointsRef q);

}  // namespace filum::geometry
