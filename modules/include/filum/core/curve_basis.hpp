// CurveBasis: the basis functions b_i(s) of a curve P(s) = Σ_i b_i(s) q_i (paper eq. 1),
// s ∈ [0, 1] the parametric abscissa along the whole curve, and BasisRow, the non-zero functions
// at one abscissa: the row of the map from a body's points to a point on its curve.
//
// In the kernel so that a body can expose its curve (CurveBody) to every library without naming
// a concrete basis; the bases themselves (uniform cubic B-spline, Catmull-Rom, NUBS) are in
// geometry/, each implementing this interface. Bases are local: at any
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

  /// Values and derivatives at s ∈ [0, 1] (clamped to it). At a knot they are the right-hand
  /// limits (the span that starts there); at s = 1 the left-hand limits of the last span.
  virtual void evaluate(double s, BasisRow& row) const = 0;
  /// The left-hand limits at s (the span that ends there; at s = 0 the first span's values).
  /// Inside a span the row is evaluate's; at a knot it is the previous span's, which gives the
  /// same P, P′ and P″ wherever the curve is C² there, and at a cut (cuts()) another point: the
  /// end of the strand before the cut.
  virtual void evaluateFromLeft(double s, BasisRow& row) const = 0;

  /// Abscissas in [0, 1], sorted, 0 and 1 included, between which every basis function is a
  /// polynomial (so that Gauss-Legendre quadrature per piece is exact).
  virtual std::vector<double> breakpoints() const = 0;
  /// Abscissas in (0, 1), sorted, where the curve is cut: C⁻¹, no basis function straddles them
  /// (a knot of multiplicity degree + 1: [Lenoir talk 2008], "local C-1 continuity => cut"). Between two
  /// consecutive cuts the curve is one strand (strands()); empty for an uncut curve.
  virtual std::vector<double> cuts() const = 0;

  virtual std::unique_ptr<CurveBasis> clone() const = 0;
};

/// One strand of a curve: the abscissas [begin, end] between two cuts (or the curve's ends).
/// P(begin) is evaluate(begin), P(end) is evaluateFromLeft(end): at a cut the two strands
/// that meet there have their own end points.
struct Strand {
  double begin = 0.0;
  double end = 1.0;
};

/// The strands of the curve in order: [0, c_1], [c_1, c_2], ..., [c_k, 1] for its cuts c_j
/// (one strand, [0, 1], for an uncut curve).
inline std::vector<Strand> strands(const CurveBasis& basis) {
  std::vector<Strand> out;
  double begin = 0.0;
  for (const double cut : basis.cuts()) {
    out.push_back({begin, cut});
    begin = cut;
  }
  out.push_back({begin, 1.0});
  return out;
}

/// The row of the strand's point at s ∈ [strand.begin, strand.end]: its end is evaluated from
/// the left (the strand's own end point at a cut), any other abscissa as evaluate does.
inline void evaluateOnStrand(const CurveBasis& basis, const Strand& strand, double s, BasisRow& row) {
  if (s >= strand.end)
    basis.evaluateFromLeft(strand.end, row);
  else
    basis.evaluate(s, row);
}

}  // namespace filum
