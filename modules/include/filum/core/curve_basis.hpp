// CurveBasis: the basis functions b_i(s) of a curve P(s) = Σ_i b_i(s) q_i (paper eq. 1),
// s ∈ [0, 1] the parametric abscissa along the whole curve, and BasisRow, the non-zero functions
// at one abscissa: the row of the map from a body's points to a point on its curve.
//
// In the kernel so that a body can expose its curve (CurveBody) to every library without naming
// a concrete basis; the bases themselves (uniform cubic B-spline, Catmull-Rom, NUBS) are in
// geometry/ (geometry/spline_basis.hpp names this interface SplineBasis). Bases are local: at any
// s only degree + 1 consecutive functions may be non-zero. All bases sum to one
// (Σ_i b_i(s) = 1, so rigid translations are exact).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace filum {

/// The non-zero basis functions at one abscissa and their first two derivatives in s.
struct BasisRow {
  static constexpr int kMaxSupport = 6;  // degree 5 + 1
  int first = 0;                         // index of the first function of the support
  int count = 0;                         // number of functions in the support (degree + 1)
  std::array<double, kMaxSupport> value{};  // b_{first+j}(s)
  std::array<double, kMaxSupport> d1{};     // b'_{first+j}(s)
  std::array<double, kMaxSupport> d2{};     // b''_{first+j}(s)
};

class CurveBasis {
 public:
  virtual ~CurveBasis() = default;

  virtual std::string name() const = 0;
  virtual int controlPointCount() const = 0;
  virtual int degree() const = 0;
  /// Parametric continuity C^k of the curve at interior knots.
  virtual int continuity() const = 0;

  /// Values and derivatives at s ∈ [0, 1] (clamped to it).
  virtual void evaluate(double s, BasisRow& row) const = 0;

  /// Abscissas in [0, 1], sorted, 0 and 1 included, between which every basis function is a
  /// polynomial (so that Gauss-Legendre quadrature per piece is exact).
  virtual std::vector<double> breakpoints() const = 0;

  virtual std::unique_ptr<CurveBasis> clone() const = 0;
};

}  // namespace filum
