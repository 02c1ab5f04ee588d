// The planar elastica by shooting — an independent reference for rod tests (it shares no code
// with the rods under test). A rod of length L, bending stiffness EI, clamped horizontally at
// s = 0 (θ the material frame's angle above the horizontal, θ(0) = 0; x along the rod, z up),
// loaded downward by its weight w (N/m) and a tip force P (N). The part beyond s pulls on the
// rest with n = (0, −F), F(s) = w (L − s) + P; Reissner's planar rod (extensible with E A,
// shearable with κ G A; both infinite: Kirchhoff's inextensible, unshearable elastica) gives
//   axial strain ε = n·d3 / E A = −F sin θ / E A,   shear γ = n·d1 / κGA = −F cos θ / κGA,
//   r' = (1 + ε) d3 + γ d1,   d3 = (cos θ, sin θ),  d1 = (−sin θ, cos θ),
//   EI θ'' = −(r' × n) = F x',   θ'(L) = 0 (free end: no moment),
// so x' = cos θ + F sin θ cos θ (1/κGA − 1/EA),  z' = sin θ − F (sin²θ / EA + cos²θ / κGA).
// Shooting on c = θ'(0): θ'(L; c) increases with c, is > 0 at c = 0 and <= 0 at
// c = −(w L²/2 + P L)/EI · max x' (x' <= 1 + F/κGA), so bisection finds the root in that bracket
// (the first equilibrium, reached by loading from the straight rod). Classical RK4 over `steps`
// steps: error O((L/steps)⁴), ~1e-13 L at the default 4000 steps for the loads of the tests.
#pragma once

#include <array>
#include <cmath>
#include <limits>

namespace filum::test {

struct ElasticaTip {
  double x, z;    // tip position (m), clamp at the origin
  double slope0;  // θ'(0) (1/m)
};

/// Stiffnesses of the rod: EI (N m²), E A and κ G A (N; infinity: inextensible, unshearable).
struct RodStiffness {
  double bending;
  double axial = std::numeric_limits<double>::infinity();
  double shear = std::numeric_limits<double>::infinity();
};

/// Integrates from s = 0 with θ'(0) = c; returns (θ, θ', x, z) at s = L.
inline std::array<double, 4> integrateElastica(double c, double length, const RodStiffness& rod, double weight,
                                               double tip, int steps) {
  const auto rhs = [&](double s, const std::array<double, 4>& y) {
    const double F = weight * (length - s) + tip, sin = std::sin(y[0]), cos = std::cos(y[0]);
    const double x1 = cos + F * sin * cos * (1.0 / rod.shear - 1.0 / rod.axial);
    const double z1 = sin - F * (sin * sin / rod.axial + cos * cos / rod.shear);
    return std::array<double, 4>{y[1], F * x1 / rod.bending, x1, z1};
  };
  std::array<double, 4> y{0.0, c, 0.0, 0.0};
  const double h = length / steps;
  for (int k = 0; k < steps; ++k) {
    const double s = k * h;
    const auto axpy = [](const std::array<double, 4>& a, double f, const std::array<double, 4>& b) {
      return std::array<double, 4>{a[0] + f * b[0], a[1] + f * b[1], a[2] + f * b[2], a[3] + f * b[3]};
    };
    const auto k1 = rhs(s, y), k2 = rhs(s + h / 2, axpy(y, h / 2, k1)), k3 = rhs(s + h / 2, axpy(y, h / 2, k2)),
               k4 = rhs(s + h, axpy(y, h, k3));
    for (int i = 0; i < 4; ++i) y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
  return y;
}

/// The clamped rod's tip under weight w (N/m) and tip force P (N), both downward.
inline ElasticaTip elasticaTip(double length, const RodStiffness& rod, double weight, double tip, int steps = 4000) {
  const double F0 = weight * length + tip;
  double lo = -(weight * length * length / 2.0 + tip * length) / rod.bending * (1.0 + F0 / rod.shear), hi = 0.0;
  for (int k = 0; k < 200 && hi - lo > 1e-15 * std::abs(lo); ++k) {
    const double mid = 0.5 * (lo + hi);
    (integrateElastica(mid, length, rod, weight, tip, steps)[1] > 0.0 ? hi : lo) = mid;
  }
  const auto y = integrateElastica(0.5 * (lo + hi), length, rod, weight, tip, steps);
  return {y[2], y[3], 0.5 * (lo + hi)};
}

}  // namespace filum::test
