// Uniform cubic B-spline basis (C2, locality l = 4), the basis the paper simulates with
// (§2: "uniform cubic BSpline for their better continuity which makes them better for
// simulation"). With n control points the curve has N = n − 3 segments; s ∈ [0, 1] maps to
// u = N s, segment j = ⌊u⌋, t = u − j, and on segment j the non-zero functions are
//   b_j = (1 − t)³/6,  b_{j+1} = (3t³ − 6t² + 4)/6,  b_{j+2} = (−3t³ + 3t² + 3t + 1)/6,  b_{j+3} = t³/6.
// The curve does not interpolate its end control points: P(0) = (q0 + 4 q1 + q2)/6.
#pragma once

#include "filum/geometry/spline_basis.hpp"

namespace filum::geometry {

class UniformCubicBSpline final : public CurveBasis {
 public:
  static constexpr int kMinimumControlPoints = 4;

  /// control_points >= 4 (throws std::invalid_argument otherwise).
  explicit UniformCubicBSpline(int control_points);

  std::string name() const override { return "uniform_cubic_bspline"; }
  int controlPointCount() const override { return n_; }
  int degree() const override { return 3; }
  int continuity() const override { return 2; }
  void evaluate(double s, BasisRow& row) const override;
  void evaluateFromLeft(double s, BasisRow& row) const override;
  std::vector<double> breakpoints() const override;
  std::vector<double> cuts() const override;
  std::unique_ptr<CurveBasis> clone() const override { return std::make_unique<UniformCubicBSpline>(n_); }

  int segmentCount() const { return n_ - 3; }

 private:
  /// The row of segment j (its functions at u = s · segments, t = u − j ∈ [0, 1]).
  void evaluateSegment(int j, double u, BasisRow& row) const;
  int n_;
};

}  // namespace filum::geometry
