// Stability map, short form (the full map is apps/bench/stability_map): the largest
// stable step of symplectic Euler and RK4 as the Young's modulus grows 100-fold, and the implicit
// schemes at the real suture's stiffness (apps/validation/stability.hpp).
// Mathematics: ω_max ∝ √E, and explicit schemes are stable for ω_max dt below a constant: 2 for
// symplectic Euler, 2√2 for RK4 (their stability intervals on the imaginary axis). So
//  - log dt_max against log E has slope −½ (asserted ±0.1: the bending part of ω_max also
//    scales as √E; the bisection resolves dt to 2^(−10) of a decade, ~0.7 %);
//  - dt_max(RK4)/dt_max(symplectic Euler) = √2 ≈ 1.41 (asserted ±0.15: the 2000-step runs
//    detect instability only once it grows past the energy bound, a few % beyond the limit);
//  - backward Euler is A-stable (and L-stable): stable at dt = 10 ms with a real suture
//    (E = 2 GPa), ω_max dt ≈ 2e4. The implicit midpoint rule is A-stable for linear problems,
//    but it does not damp stiff modes (|R(∞)| = 1) and, on this nonlinear problem (stiff
//    stretching coupled to large rotations), its energy grows at steps above ~1.5 ms (measured by
//    apps/bench/stability_map); it is stable at 0.5 ms, ω_max dt ≈ 900, far beyond any explicit
//    scheme.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "validation/stability.hpp"

namespace filum {
namespace {

TEST(StabilityMap, ExplicitStepLimitsScaleAsOneOverSquareRootOfStiffness) {
  validation::StabilityProblem problem;
  problem.control_points = 10;
  problem.steps = 600;
  const double moduli[2] = {1e6, 1e8};
  double limit[2][2];  // [integrator][modulus]
  const char* types[2] = {"SymplecticEuler", "RungeKutta4"};
  for (int i = 0; i < 2; ++i)
    for (int e = 0; e < 2; ++e) {
      problem.youngs_modulus = moduli[e];
      limit[i][e] = validation::largestStableStep({{"type", types[i]}}, problem, 1e-8, 1e-2, 10);
      std::printf("  %-16s E = %.0e Pa: largest stable dt = %.3e s\n", types[i], moduli[e], limit[i][e]);
      ASSERT_GT(limit[i][e], 0.0);
    }
  for (int i = 0; i < 2; ++i) {
    const double slope = std::log(limit[i][1] / limit[i][0]) / std::log(moduli[1] / moduli[0]);
    std::printf("  %-16s slope of log dt_max against log E: %.3f\n", types[i], slope);
    EXPECT_NEAR(slope, -0.5, 0.1) << types[i];
  }
  for (int e = 0; e < 2; ++e) EXPECT_NEAR(limit[1][e] / limit[0][e], std::sqrt(2.0), 0.15) << "E = " << moduli[e];
}

TEST(StabilityMap, ImplicitSchemesAreStableAtLargeStepsWithARealSuture) {
  validation::StabilityProblem problem;
  problem.control_points = 20;
  problem.steps = 100;
  problem.youngs_modulus = 2e9;
  std::string why;
  EXPECT_TRUE(validation::runIsStable({{"type", "ImplicitEuler"}}, problem, 1e-2, &why)) << why;
  EXPECT_TRUE(validation::runIsStable({{"type", "ImplicitMidpoint"}}, problem, 5e-4, &why)) << why;
  // and explicit RK4 is not, by far.
  EXPECT_FALSE(validation::runIsStable({{"type", "RungeKutta4"}}, problem, 1e-4));
}

}  // namespace
}  // namespace filum
