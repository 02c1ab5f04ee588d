// SplineBasis: the basis functions b_i(s) of a spline curve P(s) = Σ_i b_i(s) q_i
// (paper eq. 1), s ∈ [0, 1] the parametric abscissa along the whole curve.
//
// One interface for every basis (UniformCubicBSpline, CatmullRomSpline, NonUniformBSpline of
// degree 1..5; makeSplineBasis in spline_basis_factory.hpp builds any of them by name), so that
// mechanics, mappings and collision work with any of them. Bases are local: at any s only
// degree + 1 consecutive functions may be non-zero, reported as a BasisRow. All bases sum to
// one (Σ_i b_i(s) = 1, so rigid translations are exact); the B-spline bases are also
// non-negative (convex-hull property), Catmull-Rom is not (its functions dip to −2/27).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace filum::geometry {

/// The non-zero basis functions at one abscissa and their first two derivatives in s.
struct BasisRow {
  static constexpr int kMaxSupport = 6;  // degree 5 + 1
  int first = 0;                         // index of the first function of the support
  int count = 0;                         // number of functions in the support (degree + 1)
  std::array<double, kMaxSupport> value{};  // b_{first+j}(s)
  std::array<double, kMaxSupport> d1{};     // b'_{first+j}(s)
  std::array<double, kMaxSupport> d2{};     // b''_{first+j}(s)
};

class SplineBasis {
 public:
  virtual ~SplineBasis() = default;

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

  virtual std::unique_ptr<SplineBasis> clone() const = 0;
};

}  // namespace filum::geometry
