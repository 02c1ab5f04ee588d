// Arc length of a spline curve, L(s) = ∫_0^s |P'(σ)| dσ, by adaptive Gauss-Legendre quadrature,
// its inverse s(ℓ) and sampling at equal curvilinear spacing.
//
// Quadrature: on every polynomial piece of the basis (breakpoints()), recursively bisect
// [a, b]: with G_8 the 8-node Gauss-Legendre rule (exact to degree 15), accept the two halves
// when |G_8(a,m) + G_8(m,b) − G_8(a,b)| <= τ (b − a), τ = relative_tolerance · L_0 (L_0: one
// G_8 per piece). For an analytic integrand the halves are 2^16 times more accurate than the
// whole, so the accepted sum is far inside the tolerance; the per-width share τ (b − a) makes
// the sum of the accepted differences <= τ over s ∈ [0, 1]. |P'| is only Lipschitz where P'
// vanishes (a cusp): bisection then refines locally (depth <= 50).
//
// Inverse: ℓ ↦ s with L(s) = ℓ, safeguarded Newton on F(s) = L(s) − ℓ, F'(s) = |P'(s)|,
// inside the accepted quadrature interval that contains ℓ (bisection when Newton leaves it).
#pragma once

#include <memory>
#include <vector>

#include "filum/core/types.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::geometry {

/// Arc length of P on s ∈ [0, 1] (units of q) to `relative_tolerance` ∈ [1e-15, 1)
/// (std::invalid_argument otherwise, or if q does not have basis.controlPointCount() rows).
double curveLength(const CurveBasis& basis, ConstPointsRef q, double relative_tolerance = 1e-12);

/// The arc-length parameterisation of one curve (copies the basis and the control points).
class ArcLengthParameterization {
 public:
  ArcLengthParameterization(const CurveBasis& basis, ConstPointsRef q, double relative_tolerance = 1e-12);

  /// L(1) (units of q).
  double totalLength() const { return cumulative_.back(); }
  /// L(s), s clamped to [0, 1].
  double lengthAt(double s) const;
  /// s with L(s) = length (to round-off), length clamped to [0, L(1)]. Where the curve stands
  /// still (P' = 0 on an interval) any s of that interval may be returned.
  double abscissaAtLength(double length) const;
  /// count >= 2 abscissas with L(s_k) = k L(1)/(count − 1); s_0 = 0, s_{count−1} = 1.
  std::vector<double> equallySpacedAbscissas(int count) const;
  /// count >= 2 abscissas at equal arc length on one strand of a cut curve (CurveBasis::strands),
  /// from strand.begin to strand.end.
  std::vector<double> equallySpacedAbscissas(int count, const Strand& strand) const;
  /// The points P(s_k) at the equally spaced abscissas of `strand` (count × 3; the whole curve
  /// by default); the strand's end is its own end point (evaluateOnStrand).
  Points equallySpacedPoints(int count, const Strand& strand = {}) const;
  /// The points P(s_k) at the given abscissas of `strand` (one row each; evaluateOnStrand).
  Points pointsAt(const std::vector<double>& abscissas, const Strand& strand = {}) const;
  /// Number of accepted quadrature intervals (a measure of the work done).
  int intervalCount() const { return static_cast<int>(boundaries_.size()) - 1; }

 private:
  double speed(double s) const;                      // |P'(s)|
  double integrateSpeed(double a, double b) const;   // G_8 on [a, b]
  int intervalOf(double s) const;

  std::unique_ptr<CurveBasis> basis_;
  Points q_;
  double tolerance_;                // absolute, τ
  std::vector<double> boundaries_;  // accepted intervals [boundaries_[k], boundaries_[k+1]]
  std::vector<double> cumulative_;  // L(boundaries_[k])
};

}  // namespace filum::geometry
