#include "filum/geometry/knot_removal.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "filum/geometry/knot_vector.hpp"

namespace filum::geometry {

KnotRemoval removeKnot(const BSplineCurve& curve, double u) {
  validateBSplineCurve(curve, "removeKnot");
  const int d = curve.degree, n = curve.controlPointCount();
  const std::vector<double>& t = curve.knots;
  if (!(u > t[d] && u < t[n]) || knotMultiplicity(t, u) == 0) {
    std::ostringstream m;
    m.precision(17);
    m << "removeKnot: " << u << " is not a knot strictly inside the domain (" << t[d] << ", " << t[n] << ")";
    throw std::invalid_argument(m.str());
  }
  // τ = t without its last copy of u (index r); in τ, u falls in span k = r − 1.
  const int r = static_cast<int>(std::upper_bound(t.begin(), t.end(), u) - t.begin()) - 1;
  std::vector<double> tau = t;
  tau.erase(tau.begin() + r);
  const int k = r - 1;
  const Points& q = curve.control_points;

  // p: n − 1 points; rows outside the block are copies (p_i = q_i, i <= k − d; p_i = q_{i+1}, i >= k).
  Points p(n - 1, 3);
  p.topRows(k - d + 1) = q.topRows(k - d + 1);
  p.bottomRows(n - 1 - k) = q.bottomRows(n - 1 - k);

  // Bidiagonal rows i = k−d+1..k: α_i p_i + (1 − α_i) p_{i−1} = q_i; unknowns p_{k−d+1}..p_{k−1}.
  const int rows = d, unknowns = d - 1;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, unknowns);
  Eigen::MatrixXd b(rows, 3);
  double alpha[kMaximumSplineDegree + 1];
  for (int row = 0; row < rows; ++row) {
    const int i = k - d + 1 + row;
    alpha[row] = (u - tau[i]) / (tau[i + d] - tau[i]);
    b.row(row) = q.row(i);
    // p_i (column i − (k−d+1)) unless i = k (fixed); p_{i−1} (column i − 1 − (k−d+1)) unless i − 1 = k − d.
    if (i <= k - 1) A(row, i - (k - d + 1)) = alpha[row];
    else b.row(row) -= alpha[row] * p.row(k);
    if (i - 1 >= k - d + 1) A(row, i - 1 - (k - d + 1)) = 1.0 - alpha[row];
    else b.row(row) -= (1.0 - alpha[row]) * p.row(k - d);
  }
  if (unknowns > 0) {
    const Eigen::MatrixXd x = A.colPivHouseholderQr().solve(b);
    for (int c = 0; c < unknowns; ++c) p.row(k - d + 1 + c) = x.row(c);
  }
  // Bound: max_i |q_i − (A p)_i| over the bidiagonal rows (the other rows are exact).
  double bound = 0.0;
  for (int row = 0; row < rows; ++row) {
    const int i = k - d + 1 + row;
    const Eigen::RowVector3d reinserted = alpha[row] * p.row(i) + (1.0 - alpha[row]) * p.row(i - 1);
    bound = std::max(bound, (q.row(i) - reinserted).norm());
  }
  return KnotRemoval{BSplineCurve{d, std::move(tau), std::move(p)}, bound, 1};
}

KnotRemoval simplifyCurve(const BSplineCurve& curve, double tolerance) {
  validateBSplineCurve(curve, "simplifyCurve");
  if (!(tolerance >= 0.0))
    throw std::invalid_argument("simplifyCurve: tolerance must be >= 0, got " + std::to_string(tolerance));
  KnotRemoval result{curve, 0.0, 0};
  for (;;) {
    const BSplineCurve& c = result.curve;
    const int d = c.degree, n = c.controlPointCount();
    if (n <= d + 1) break;  // a single polynomial piece is left
    const std::vector<double> distinct = distinctDomainKnots(d, n, c.knots);
    KnotRemoval best{c, std::numeric_limits<double>::infinity(), 0};
    for (std::size_t j = 1; j + 1 < distinct.size(); ++j) {
      KnotRemoval trial = removeKnot(c, distinct[j]);
      if (trial.error_bound < best.error_bound) best = std::move(trial);
    }
    if (!(result.error_bound + best.error_bound <= tolerance)) break;
    result.curve = std::move(best.curve);
    result.error_bound += best.error_bound;
    ++result.removed;
  }
  return result;
}

}  // namespace filum::geometry
