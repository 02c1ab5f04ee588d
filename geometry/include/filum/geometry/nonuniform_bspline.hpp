// Non-uniform B-spline basis (NUBS) of any degree d in 1..5 on any valid knot vector, clamped
// or not. Values and derivatives come from the Cox–de Boor recurrence
//   B_{i,0}(u) = 1 if t_i <= u < t_{i+1}, else 0,
//   B_{i,r}(u) = (u − t_i)/(t_{i+r} − t_i) B_{i,r−1}(u) + (t_{i+r+1} − u)/(t_{i+r+1} − t_{i+1}) B_{i+1,r−1}(u),
// organised as in Piegl & Tiller, "The NURBS Book", algorithm A2.2 (the d + 1 non-zero functions
// of one span in O(d²), no allocation, one instantiation per degree), and the derivative formula
//   B'_{i,r}(u) = r [ B_{i,r−1}(u)/(t_{i+r} − t_i) − B_{i+1,r−1}(u)/(t_{i+r+1} − t_{i+1}) ]
// (de Boor ch. X), applied to the degree d − 1 values for B', and twice (degree d − 2 values →
// degree d − 1 derivatives → B'') for B''.
//
// Parameterisation: s ∈ [0, 1] is mapped affinely onto the valid domain [t_d, t_n] (n control
// points, knots t_0..t_{n+d}): u(s) = t_d + s (t_n − t_d), so d^k/ds^k = (t_n − t_d)^k d^k/du^k.
// Inside the domain the functions are non-negative and sum to one. At an interior knot of
// multiplicity m the curve is C^{d−m} (m = d + 1: the curve may break there — a cut, [Lenoir talk 2008]).
// Derivatives at a knot are the right-hand limits (the span with t_k <= u < t_{k+1}); at
// u = t_n they are the left-hand limits of the last span.
#pragma once

#include <vector>

#include "filum/geometry/spline_basis.hpp"

namespace filum::geometry {

class NonUniformBSpline final : public CurveBasis {
 public:
  /// degree in [1, 5]; knots as validateKnotVector (knot_vector.hpp) requires, with
  /// knots.size() − degree − 1 control points (at least degree + 1). Knots are in any unit
  /// (only their ratios matter for s). Throws std::invalid_argument on bad input.
  NonUniformBSpline(int degree, std::vector<double> knots);

  std::string name() const override { return "nubs"; }
  int controlPointCount() const override { return n_; }
  int degree() const override { return d_; }
  /// min over interior domain knots of d − multiplicity (−1 if some knot has multiplicity d + 1);
  /// d − 1 when the domain has no interior knot (one polynomial piece).
  int continuity() const override { return continuity_; }
  void evaluate(double s, BasisRow& row) const override;
  void evaluateFromLeft(double s, BasisRow& row) const override;
  /// The distinct knots of [t_d, t_n] mapped to [0, 1].
  std::vector<double> breakpoints() const override { return breakpoints_; }
  /// The interior knots of multiplicity d + 1, mapped to [0, 1].
  std::vector<double> cuts() const override { return cuts_; }
  std::unique_ptr<CurveBasis> clone() const override { return std::make_unique<NonUniformBSpline>(*this); }

  const std::vector<double>& knots() const { return knots_; }
  double domainStart() const { return knots_[d_]; }  // t_d
  double domainEnd() const { return knots_[n_]; }    // t_n
  /// u(s) = t_d + s (t_n − t_d), s clamped to [0, 1]; u(1) = t_n exactly.
  double parameterAt(double s) const;
  /// s(u) = (u − t_d)/(t_n − t_d), the inverse of parameterAt.
  double abscissaAt(double u) const;
  /// Values and derivatives with respect to the knot parameter u (not s), u clamped to the
  /// domain; right-hand limits at a knot.
  void evaluateAtParameter(double u, BasisRow& row) const;

 private:
  int d_;
  int n_;
  std::vector<double> knots_;
  std::vector<double> breakpoints_;
  int continuity_;
  std::vector<double> cuts_;
  void evaluateOnSide(double s, bool from_left, BasisRow& row) const;
  /// The span whose closed interval ends at u, from span k (the one that holds u).
  int leftSpan(int k, double u) const;
  /// The d + 1 functions of span k at u and their u-derivatives.
  void evaluateInSpan(int k, double u, BasisRow& row) const;
};

}  // namespace filum::geometry
