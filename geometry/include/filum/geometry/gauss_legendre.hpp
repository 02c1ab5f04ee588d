// Gauss-Legendre quadrature: k nodes integrate polynomials of degree <= 2k − 1 exactly.
// Used for the exact mass matrix M_ij = m ∫ b_i b_j ds (paper eq. 3) and arc lengths.
#pragma once

#include <vector>

namespace filum::geometry {

struct QuadratureRule {
  std::vector<double> nodes;    // on [−1, 1]
  std::vector<double> weights;  // sum to 2
};

/// The k-point rule (k >= 1), nodes found by Newton iteration on P_k to machine precision.
QuadratureRule gaussLegendre(int k);

/// ∫_a^b f(x) dx with the rule, mapped to [a, b].
template <class F>
double integrate(const QuadratureRule& rule, double a, double b, F&& f) {
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  double sum = 0.0;
  for (std::size_t i = 0; i < rule.nodes.size(); ++i) sum += rule.weights[i] * f(mid + half * rule.nodes[i]);
  return half * sum;
}

}  // namespace filum::geometry
