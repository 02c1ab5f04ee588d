#include "filum/geometry/gauss_legendre.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace filum::geometry {

QuadratureRule gaussLegendre(int k) {
  if (k < 1) throw std::invalid_argument("gaussLegendre needs k >= 1");
  QuadratureRule rule;
  rule.nodes.resize(k);
  rule.weights.resize(k);
  for (int i = 0; i < (k + 1) / 2; ++i) {
    // Initial guess (Tricomi), then Newton on P_k(x) with the three-term recurrence.
    double x = std::cos(std::numbers::pi * (i + 0.75) / (k + 0.5));
    // P_k(x) and P_k'(x) by the recurrence (m P_m = (2m − 1) x P_{m−1} − (m − 1) P_{m−2}).
    auto legendre = [k](double x, double& dp) {
      double p0 = 1.0, p1 = x;
      for (int m = 2; m <= k; ++m) {
        const double p2 = ((2.0 * m - 1.0) * x * p1 - (m - 1.0) * p0) / m;
        p0 = p1;
        p1 = p2;
      }
      dp = k * (x * p1 - p0) / (x * x - 1.0);  // P_k'(x)
      return p1;
    };
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      const double dx = legendre(x, dp) / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    legendre(x, dp);  // P_k' at the final node, for the weight
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);  // w_i = 2 / ((1 − x_i²) P_k'(x_i)²)
    rule.nodes[i] = -x;
    rule.nodes[k - 1 - i] = x;
    rule.weights[i] = rule.weights[k - 1 - i] = w;
  }
  if (k % 2 == 1) rule.nodes[k / 2] = 0.0;
  return rule;
}

}  // namespace filum::geometry
