// Gauss-Legendre rules: the exactness the mass matrix and the arc length rely on.
#include <gtest/gtest.h>

#include <cmath>

#include "filum/geometry/gauss_legendre.hpp"

namespace filum::geometry {
namespace {

TEST(GaussLegendre, KPointsIntegrateDegreeTwoKMinusOneExactly) {
  // ∫_{−1}^{1} x^m dx = 2/(m + 1) for even m, 0 for odd m, exact for m <= 2k − 1; the nodes come
  // from Newton to 1e-16, so the error is round-off of k terms: 1e-15.
  for (int k = 1; k <= 12; ++k) {
    const QuadratureRule rule = gaussLegendre(k);
    for (int m = 0; m <= 2 * k - 1; ++m) {
      const double exact = m % 2 == 0 ? 2.0 / (m + 1) : 0.0;
      EXPECT_NEAR(integrate(rule, -1.0, 1.0, [&](double x) { return std::pow(x, m); }), exact, 1e-15)
          << "k = " << k << " m = " << m;
    }
  }
  EXPECT_THROW(gaussLegendre(0), std::invalid_argument);
}

}  // namespace
}  // namespace filum::geometry
