// Uniform Catmull-Rom spline basis (Catmull & Rom 1974, "A class of local interpolating
// splines"): a C1 cubic that interpolates its control points, tension 1/2, uniform
// parameterisation. On segment j (local t ∈ [0, 1]) with control points q_j..q_{j+3}:
//   P(t) = ½ [ (−t³ + 2t² − t) q_j + (3t³ − 5t² + 2) q_{j+1} + (−3t³ + 4t² + t) q_{j+2} + (t³ − t²) q_{j+3} ],
// so P(0) = q_{j+1}, P(1) = q_{j+2}, P'(0) = (q_{j+2} − q_j)/2, P'(1) = (q_{j+3} − q_{j+1})/2
// (tangents in t; C1 across segments, P'' jumps in general).
//
// End segments (our choice, same layout as the uniform cubic B-spline): with n control points
// there are N = n − 3 segments; s ∈ [0, 1] maps to u = N s, segment j = ⌊u⌋, t = u − j, and the
// curve runs from P(0) = q_1 to P(1) = q_{n−2}, passing through q_1..q_{n−2} at s = (i − 1)/N.
// The end points q_0 and q_{n−1} only set the end tangents P'(0) = N(q_2 − q_0)/2,
// P'(1) = N(q_{n−1} − q_{n−3})/2. Locality is 4 everywhere and a scene's control points for a
// uniform cubic B-spline (straight thread from q_1 to q_{n−2}) work unchanged. To pass through
// ALL of m given points, add phantom ends with withPhantomEndPoints() (reflections
// q_{−1} = 2 q_0 − q_1, q_m = 2 q_{m−1} − q_{m−2}, i.e. zero end curvature of the chord polygon).
//
// Unlike B-splines, Catmull-Rom functions take negative values (down to −2/27 at t = 1/3 and
// 2/3): the curve is NOT inside the convex hull of its control points.
#pragma once

#include "filum/core/types.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::geometry {

class CatmullRomSpline final : public CurveBasis {
 public:
  static constexpr int kMinimumControlPoints = 4;

  /// control_points >= 4 (throws std::invalid_argument otherwise).
  explicit CatmullRomSpline(int control_points);

  std::string name() const override { return "catmull_rom"; }
  int controlPointCount() const override { return n_; }
  int degree() const override { return 3; }
  int continuity() const override { return 1; }
  void evaluate(double s, BasisRow& row) const override;
  void evaluateFromLeft(double s, BasisRow& row) const override;
  std::vector<double> breakpoints() const override;
  std::vector<double> cuts() const override;
  std::unique_ptr<CurveBasis> clone() const override { return std::make_unique<CatmullRomSpline>(n_); }

  int segmentCount() const { return n_ - 3; }
  /// Abscissa where the curve passes through control point i (1 <= i <= n − 2): s = (i − 1)/N.
  double abscissaOfControlPoint(int i) const;

 private:
  /// The row of segment j (its functions at u = s · segments, t = u − j ∈ [0, 1]).
  void evaluateSegment(int j, double u, BasisRow& row) const;
  int n_;
};

/// m >= 2 points to interpolate → m + 2 control points with reflected phantom ends
/// q_{−1} = 2 q_0 − q_1 and q_m = 2 q_{m−1} − q_{m−2}; the Catmull-Rom curve on them passes
/// through every given point (first at s = 0, last at s = 1).
Points withPhantomEndPoints(ConstPointsRef points);

}  // namespace filum::geometry
