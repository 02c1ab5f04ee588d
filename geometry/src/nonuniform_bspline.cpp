#include "filum/geometry/nonuniform_bspline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "filum/geometry/knot_vector.hpp"

namespace filum::geometry {

namespace {

int controlPointsOf(int degree, std::size_t knot_count) {
  const long n = static_cast<long>(knot_count) - degree - 1;
  if (degree < kMinimumSplineDegree || degree > kMaximumSplineDegree)
    throw std::invalid_argument("NonUniformBSpline: degree must be in [1, 5], got " + std::to_string(degree));
  if (n < degree + 1)
    throw std::invalid_argument("NonUniformBSpline: " + std::to_string(knot_count) + " knots give " +
                                std::to_string(n) + " control points for degree " + std::to_string(degree) +
                                "; at least degree + 1 = " + std::to_string(degree + 1) +
                                " are needed (knots.size() = control points + degree + 1)");
  return static_cast<int>(n);
}

}  // namespace

NonUniformBSpline::NonUniformBSpline(int degree, std::vector<double> knots)
    : d_(degree), n_(controlPointsOf(degree, knots.size())), knots_(std::move(knots)) {
  validateKnotVector(d_, n_, knots_, "NonUniformBSpline");
  const std::vector<double> distinct = distinctDomainKnots(d_, n_, knots_);
  const double t0 = knots_[d_], range = knots_[n_] - knots_[d_];
  breakpoints_.resize(distinct.size());
  for (std::size_t k = 0; k < distinct.size(); ++k) breakpoints_[k] = (distinct[k] - t0) / range;
  breakpoints_.front() = 0.0;
  breakpoints_.back() = 1.0;
  // C^{d − m} at an interior knot of multiplicity m.
  continuity_ = d_ - 1;
  int lowest = d_;
  for (std::size_t k = 1; k + 1 < distinct.size(); ++k)
    lowest = std::min(lowest, d_ - knotMultiplicity(knots_, distinct[k]));
  if (distinct.size() > 2) continuity_ = lowest;
  // Cuts: interior knots of multiplicity d + 1 (no basis function straddles them).
  for (std::size_t k = 1; k + 1 < distinct.size(); ++k)
    if (knotMultiplicity(knots_, distinct[k]) == d_ + 1) cuts_.push_back(breakpoints_[k]);
}

double NonUniformBSpline::parameterAt(double s) const {
  if (!(s > 0.0)) return knots_[d_];
  if (!(s < 1.0)) return knots_[n_];
  return std::min(knots_[d_] + s * (knots_[n_] - knots_[d_]), knots_[n_]);
}

double NonUniformBSpline::abscissaAt(double u) const { return (u - knots_[d_]) / (knots_[n_] - knots_[d_]); }

void NonUniformBSpline::evaluate(double s, BasisRow& row) const { evaluateOnSide(s, false, row); }

void NonUniformBSpline::evaluateFromLeft(double s, BasisRow& row) const { evaluateOnSide(s, true, row); }

void NonUniformBSpline::evaluateOnSide(double s, bool from_left, BasisRow& row) const {
  // u(s) within a few ulps of a knot is that knot: a cut's abscissa (cuts(), s = (u − t_d)/range
  // rounded) maps back onto its knot, so that evaluate and evaluateFromLeft pick the strands
  // after and before it. Elsewhere the basis is continuous and the snap changes round-off only.
  double u = parameterAt(s);
  int k = findKnotSpan(d_, n_, knots_, u);
  const double snap = 8.0 * std::numeric_limits<double>::epsilon() * (std::abs(knots_[d_]) + std::abs(knots_[n_]));
  if (k + 1 < n_ && u != knots_[k + 1] && knots_[k + 1] - u <= snap) {
    u = knots_[k + 1];
    k = findKnotSpan(d_, n_, knots_, u);  // the span that starts there (rare: only when snapped)
  } else if (u - knots_[k] <= snap) {
    u = knots_[k];
  }
  evaluateInSpan(from_left ? leftSpan(k, u) : k, u, row);
  // Chain rule: d/ds = (t_n − t_d) d/du.
  const double scale = knots_[n_] - knots_[d_];
  const double scale2 = scale * scale;
  for (int j = 0; j <= d_; ++j) {
    row.d1[j] *= scale;
    row.d2[j] *= scale2;
  }
}

int NonUniformBSpline::leftSpan(int k, double u) const {
  // The last non-empty span that ends at u (t_k < u <= t_{k+1}); the recurrence holds on the
  // closed span, so its functions at its right end are the left-hand limits.
  while (k > d_ && !(knots_[k] < u)) --k;
  return k;
}

namespace {

/// All non-zero B-splines of degree P on span k (t_k <= u < t_{k+1}) and their first two
/// u-derivatives, loops unrolled by the compiler for each degree.
template <int P>
void evaluateSpan(const double* t, int k, double u, BasisRow& row) {
  // Cox–de Boor triangle (Piegl & Tiller A2.2, non-negative form): after level j, N[j][r] holds
  // B_{k−j+r, j}(u), r = 0..j. Every factor is >= 0 on the span, so the values are >= 0 exactly.
  double N[P + 1][P + 1];
  double left[P + 1], right[P + 1];
  N[0][0] = 1.0;
  for (int j = 1; j <= P; ++j) {
    left[j] = u - t[k + 1 - j];  // u − t_{k+1−j} >= 0
    right[j] = t[k + j] - u;     // t_{k+j} − u >= 0
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      // B_{i,j} = (u − t_i)/(t_{i+j} − t_i) B_{i,j−1} + (t_{i+j+1} − u)/(t_{i+j+1} − t_{i+1}) B_{i+1,j−1};
      // both neighbours share the denominator right[r+1] + left[j−r] = t_{k+r+1} − t_{k+r+1−j} > 0.
      const double temp = N[j - 1][r] / (right[r + 1] + left[j - r]);
      N[j][r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j][j] = saved;
  }
  for (int r = 0; r <= P; ++r) row.value[r] = N[P][r];

  // B'_{i,p} = p [ B_{i,p−1}/(t_{i+p} − t_i) − B_{i+1,p−1}/(t_{i+p+1} − t_{i+1}) ], applied at
  // degree P (for d1) and P − 1 (for the derivatives of degree P − 1 that d2 differentiates again).
  // For i = k − p + r the denominators are t_{k+r} − t_{k−p+r} (r = 1..p), all > 0 on the span.
  auto derivative = [&](int p, const double* lower, double* out) {
    // lower[r] = B_{k−p+1+r, p−1}, r = 0..p−1; out[r] = B'_{k−p+r, p}, r = 0..p.
    double previous = 0.0;  // B_{i, p−1}/(t_{i+p} − t_i) for the current i (0 for r = 0)
    for (int r = 0; r < p; ++r) {
      const double scaled = lower[r] / (t[k + r + 1] - t[k - p + r + 1]);
      out[r] = p * (previous - scaled);
      previous = scaled;
    }
    out[p] = p * previous;
  };
  derivative(P, N[P - 1], row.d1.data());
  if constexpr (P >= 2) {
    double lower_derivative[P];
    derivative(P - 1, N[P - 2], lower_derivative);  // B'_{k−P+1+r, P−1}, r = 0..P−1
    derivative(P, lower_derivative, row.d2.data());  // the same formula on the derivatives
  } else {
    for (int r = 0; r <= P; ++r) row.d2[r] = 0.0;
  }
  for (int r = P + 1; r < BasisRow::kMaxSupport; ++r) row.value[r] = row.d1[r] = row.d2[r] = 0.0;
}

}  // namespace

void NonUniformBSpline::evaluateAtParameter(double u, BasisRow& row) const {
  u = std::clamp(u, knots_[d_], knots_[n_]);
  evaluateInSpan(findKnotSpan(d_, n_, knots_, u), u, row);
}

void NonUniformBSpline::evaluateInSpan(int k, double u, BasisRow& row) const {
  const double* t = knots_.data();
  row.first = k - d_;
  row.count = d_ + 1;
  switch (d_) {
    case 1: evaluateSpan<1>(t, k, u, row); break;
    case 2: evaluateSpan<2>(t, k, u, row); break;
    case 3: evaluateSpan<3>(t, k, u, row); break;
    case 4: evaluateSpan<4>(t, k, u, row); break;
    default: evaluateSpan<5>(t, k, u, row); break;
  }
}

}  // namespace filum::geometry
