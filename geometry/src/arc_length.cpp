#include "filum/geometry/arc_length.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "filum/geometry/gauss_legendre.hpp"
#include "filum/geometry/spline_curve.hpp"

namespace filum::geometry {

namespace {

constexpr int kNodes = 8;       // G_8, exact for polynomials of degree <= 15
constexpr int kMaximumDepth = 50;

const QuadratureRule& rule8() {
  static const QuadratureRule rule = gaussLegendre(kNodes);
  return rule;
}

void checkInput(const CurveBasis& basis, ConstPointsRef q, double relative_tolerance, const char* what) {
  if (q.rows() != basis.controlPointCount())
    throw std::invalid_argument(std::string(what) + ": the basis has " + std::to_string(basis.controlPointCount()) +
                                " control points but q has " + std::to_string(q.rows()) + " rows");
  if (!(relative_tolerance >= 1e-15 && relative_tolerance < 1.0))
    throw std::invalid_argument(std::string(what) + ": relative_tolerance must be in [1e-15, 1), got " +
                                std::to_string(relative_tolerance));
}

struct SpeedIntegrator {
  const CurveBasis& basis;
  ConstPointsRef q;
  mutable BasisRow row;

  double speed(double s) const {
    basis.evaluate(s, row);
    return curveTangent(row, q).norm();
  }
  double operator()(double a, double b) const {
    return integrate(rule8(), a, b, [&](double s) { return speed(s); });
  }
};

/// Adaptive bisection of [a, b] (whole = G_8(a, b)); appends accepted interval ends and lengths.
void adaptive(const SpeedIntegrator& g, double a, double b, double whole, double tolerance, int depth,
              std::vector<double>& ends, std::vector<double>& lengths) {
  const double m = 0.5 * (a + b);
  const double left = g(a, m), right = g(m, b);
  // Accept when the halves agree with the whole to the interval's share of the tolerance.
  if (std::abs(left + right - whole) <= tolerance * (b - a) || depth >= kMaximumDepth || !(m > a && m < b)) {
    ends.push_back(m);
    lengths.push_back(left);
    ends.push_back(b);
    lengths.push_back(right);
    return;
  }
  adaptive(g, a, m, left, tolerance, depth + 1, ends, lengths);
  adaptive(g, m, b, right, tolerance, depth + 1, ends, lengths);
}

/// Accepted intervals of the whole curve: ends (without 0) and their lengths.
double buildTable(const CurveBasis& basis, ConstPointsRef q, double relative_tolerance, std::vector<double>& ends,
                  std::vector<double>& lengths) {
  const SpeedIntegrator g{basis, q, {}};
  const std::vector<double> pieces = basis.breakpoints();
  std::vector<double> whole(pieces.size() - 1);
  double estimate = 0.0;
  for (std::size_t k = 0; k + 1 < pieces.size(); ++k) estimate += whole[k] = g(pieces[k], pieces[k + 1]);
  const double tolerance = relative_tolerance * estimate;  // τ, absolute
  for (std::size_t k = 0; k + 1 < pieces.size(); ++k) {
    if (!(pieces[k + 1] > pieces[k])) continue;
    if (estimate == 0.0) {
      ends.push_back(pieces[k + 1]);
      lengths.push_back(0.0);
      continue;
    }
    adaptive(g, pieces[k], pieces[k + 1], whole[k], tolerance, 0, ends, lengths);
  }
  return tolerance;
}

}  // namespace

double curveLength(const CurveBasis& basis, ConstPointsRef q, double relative_tolerance) {
  checkInput(basis, q, relative_tolerance, "curveLength");
  std::vector<double> ends, lengths;
  buildTable(basis, q, relative_tolerance, ends, lengths);
  double total = 0.0;
  for (double l : lengths) total += l;
  return total;
}

ArcLengthParameterization::ArcLengthParameterization(const CurveBasis& basis, ConstPointsRef q,
                                                     double relative_tolerance)
    : basis_(basis.clone()), q_(q) {
  checkInput(basis, q, relative_tolerance, "ArcLengthParameterization");
  std::vector<double> ends, lengths;
  tolerance_ = buildTable(*basis_, q_, relative_tolerance, ends, lengths);
  boundaries_.reserve(ends.size() + 1);
  cumulative_.reserve(ends.size() + 1);
  boundaries_.push_back(0.0);
  cumulative_.push_back(0.0);
  for (std::size_t k = 0; k < ends.size(); ++k) {
    boundaries_.push_back(ends[k]);
    cumulative_.push_back(cumulative_.back() + lengths[k]);
  }
  boundaries_.back() = 1.0;
}

double ArcLengthParameterization::speed(double s) const {
  BasisRow row;
  basis_->evaluate(s, row);
  return curveTangent(row, q_).norm();
}

double ArcLengthParameterization::integrateSpeed(double a, double b) const {
  return integrate(rule8(), a, b, [&](double s) { return speed(s); });
}

int ArcLengthParameterization::intervalOf(double s) const {
  // Last k with boundaries_[k] <= s, at most intervalCount() − 1.
  const auto it = std::upper_bound(boundaries_.begin(), boundaries_.end(), s);
  const int k = static_cast<int>(it - boundaries_.begin()) - 1;
  return std::clamp(k, 0, intervalCount() - 1);
}

double ArcLengthParameterization::lengthAt(double s) const {
  s = std::clamp(s, 0.0, 1.0);
  const int k = intervalOf(s);
  if (s == boundaries_[k]) return cumulative_[k];
  return cumulative_[k] + integrateSpeed(boundaries_[k], s);
}

double ArcLengthParameterization::abscissaAtLength(double length) const {
  const double total = totalLength();
  if (!(length > 0.0)) return 0.0;
  if (!(length < total)) return 1.0;
  // Interval k with cumulative_[k] < length <= cumulative_[k+1].
  const auto it = std::lower_bound(cumulative_.begin(), cumulative_.end(), length);
  const int k = std::clamp(static_cast<int>(it - cumulative_.begin()) - 1, 0, intervalCount() - 1);
  const double a = boundaries_[k], base = cumulative_[k], span = cumulative_[k + 1] - base;
  double lo = a, hi = boundaries_[k + 1];  // bracket of the root, shrinks
  if (!(span > 0.0)) return a;
  // F(s) = L(s) − ℓ, increasing; start from linear interpolation of the interval.
  double s = lo + (hi - lo) * std::clamp((length - base) / span, 0.0, 1.0);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double f = base + (s > a ? integrateSpeed(a, s) : 0.0) - length;
    if (f == 0.0) return s;
    if (f < 0.0) lo = s; else hi = s;
    const double df = speed(s);
    double next = df > 0.0 ? s - f / df : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // Newton left the bracket: bisect
    if (std::abs(next - s) <= 2.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(s)) ||
        !(hi > lo))
      return next;
    s = next;
  }
  return s;
}

std::vector<double> ArcLengthParameterization::equallySpacedAbscissas(int count) const {
  if (count < 2)
    throw std::invalid_argument("equallySpacedAbscissas: count must be >= 2, got " + std::to_string(count));
  std::vector<double> s(count);
  const double step = totalLength() / (count - 1);
  for (int k = 0; k < count; ++k) s[k] = abscissaAtLength(k * step);
  s.front() = 0.0;
  s.back() = 1.0;
  return s;
}

std::vector<double> ArcLengthParameterization::equallySpacedAbscissas(int count, const Strand& strand) const {
  if (count < 2)
    throw std::invalid_argument("equallySpacedAbscissas: count must be >= 2, got " + std::to_string(count));
  std::vector<double> s(count);
  const double from = lengthAt(strand.begin), to = lengthAt(strand.end);
  for (int k = 0; k < count; ++k)
    s[k] = std::clamp(abscissaAtLength(from + (to - from) * k / (count - 1)), strand.begin, strand.end);
  s.front() = strand.begin;
  s.back() = strand.end;
  return s;
}

Points ArcLengthParameterization::equallySpacedPoints(int count, const Strand& strand) const {
  return pointsAt(equallySpacedAbscissas(count, strand), strand);
}

Points ArcLengthParameterization::pointsAt(const std::vector<double>& abscissas, const Strand& strand) const {
  Points out(static_cast<Eigen::Index>(abscissas.size()), 3);
  BasisRow row;
  for (std::size_t k = 0; k < abscissas.size(); ++k) {
    evaluateOnStrand(*basis_, strand, abscissas[k], row);
    out.row(static_cast<Eigen::Index>(k)) = curvePoint(row, q_).transpose();
  }
  return out;
}

}  // namespace filum::geometry
