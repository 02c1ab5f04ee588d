#include "filum/geometry/knot_vector.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace filum::geometry {

namespace {

[[noreturn]] void fail(const char* what, const std::string& message) {
  throw std::invalid_argument(std::string(what) + ": " + message);
}

}  // namespace

void validateKnotVector(int degree, int control_points, const std::vector<double>& knots, const char* what) {
  if (degree < kMinimumSplineDegree || degree > kMaximumSplineDegree)
    fail(what, "degree must be in [1, 5], got " + std::to_string(degree));
  if (control_points < degree + 1)
    fail(what, "a degree " + std::to_string(degree) + " B-spline needs at least " + std::to_string(degree + 1) +
                   " control points, got " + std::to_string(control_points));
  const std::size_t expected = static_cast<std::size_t>(control_points + degree + 1);
  if (knots.size() != expected)
    fail(what, "expected control_points + degree + 1 = " + std::to_string(expected) + " knots, got " +
                   std::to_string(knots.size()));
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (!std::isfinite(knots[i])) fail(what, "knot " + std::to_string(i) + " is not finite");
    if (i > 0 && knots[i] < knots[i - 1]) {
      std::ostringstream m;
      m.precision(17);
      m << "knots must be non-decreasing, but t_" << i << " = " << knots[i] << " < t_" << i - 1 << " = "
        << knots[i - 1];
      fail(what, m.str());
    }
  }
  for (std::size_t i = 0; i < knots.size();) {
    std::size_t j = i;
    while (j < knots.size() && knots[j] == knots[i]) ++j;
    if (static_cast<int>(j - i) > degree + 1) {
      std::ostringstream m;
      m.precision(17);
      m << "knot " << knots[i] << " has multiplicity " << j - i << " > degree + 1 = " << degree + 1
        << " (a basis function would vanish identically)";
      fail(what, m.str());
    }
    i = j;
  }
  const int d = degree, n = control_points;
  if (!(knots[d] < knots[d + 1]) || !(knots[n - 1] < knots[n])) {
    std::ostringstream m;
    m.precision(17);
    m << "the domain [t_d, t_n] = [" << knots[d] << ", " << knots[n]
      << "] must have simple ends (t_d < t_{d+1}, t_{n-1} < t_n), otherwise a basis function is zero on it";
    fail(what, m.str());
  }
}

int findKnotSpan(int degree, int control_points, const std::vector<double>& knots, double u) {
  const int d = degree, n = control_points;
  if (!(u < knots[n])) {
    // Last non-empty span: t_{n−1} < t_n is guaranteed by validateKnotVector.
    return n - 1;
  }
  if (u <= knots[d]) return d;
  // Largest k in [d, n − 1] with t_k <= u: upper_bound finds the first knot > u.
  const auto it = std::upper_bound(knots.begin() + d, knots.begin() + n, u);
  return static_cast<int>(it - knots.begin()) - 1;
}

int knotMultiplicity(const std::vector<double>& knots, double u) {
  const auto range = std::equal_range(knots.begin(), knots.end(), u);
  return static_cast<int>(range.second - range.first);
}

std::vector<double> distinctDomainKnots(int degree, int control_points, const std::vector<double>& knots) {
  std::vector<double> out;
  for (int i = degree; i <= control_points; ++i)
    if (out.empty() || knots[i] != out.back()) out.push_back(knots[i]);
  return out;
}

std::vector<double> uniformKnots(int degree, int control_points) {
  std::vector<double> t(static_cast<std::size_t>(control_points + degree + 1));
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = static_cast<double>(i) - degree;
  return t;
}

std::vector<double> clampedUniformKnots(int degree, int control_points) {
  if (control_points < degree + 1)
    throw std::invalid_argument("clampedUniformKnots: need at least degree + 1 = " + std::to_string(degree + 1) +
                                " control points, got " + std::to_string(control_points));
  std::vector<double> t(static_cast<std::size_t>(control_points + degree + 1));
  const int pieces = control_points - degree;
  for (std::size_t i = 0; i < t.size(); ++i)
    t[i] = std::clamp(static_cast<double>(i) - degree, 0.0, static_cast<double>(pieces));
  return t;
}

}  // namespace filum::geometry
