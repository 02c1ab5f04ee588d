// Energy behaviour of the integrators:
//  - undamped symplectic Euler keeps the energy bounded over 10^5 steps: no drift, only the
//    O(h ω) oscillation of a symplectic scheme (it conserves a modified energy H̃ = H + O(h));
//  - implicit Euler never increases the energy of a system with a convex energy, whatever the
//    step: for convex E, E(q1) <= E(q0) + ∇E(q1)·(q1 − q0) = E(q0) − h Q(q1)·v1, and
//    ½|v1|²_M − ½|v0|²_M = h v1·Q(q1) − ½|v1 − v0|²_M (backward Euler: M (v1 − v0) = h Q(q1)),
//    so E_{n+1} − E_n <= −½ |v1 − v0|²_M <= 0. A thread in tension (a taut string) has a convex
//    stretching energy (∂²/∂x² of (|x|² − a0²)² is 4(|x|² − a0²) I + 8 x xᵀ, positive definite
//    for |x| >= a0) and the quadratic bending is convex. The fixed ends' constraint forces do no
//    work while the ends sit on their targets (g = ġ = 0 up to round-off, so L v1 = 0).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/mechanics_scenes.hpp"
#include "validation/taut_string.hpp"

namespace filum {
namespace {

using nlohmann::json;

TEST(EnergyBehaviour, UndampedSymplecticEulerKeepsTheEnergyBoundedOver1e5Steps) {
  // A thread held at one end (FixedPointConstraint), released horizontally under gravity, with
  // Green-Lagrange stretching and quadratic bending of a soft material (E = 1 MPa), no damping.
  // Its stiffest mode has ω_max ≈ 1.6e4 rad/s; dt = 2e-5 s (ω_max h ≈ 0.32 < 2, stable), 10^5
  // steps = 2 s, ~20 swings. A symplectic scheme's energy error oscillates with amplitude
  // O(h ω) times the energy exchanged; asserted: (max − min)/(m g L) < 0.1 over the run (ω_max h
  // ≈ 0.32 bounds it; measured ~1e-2), and no drift: backward error analysis gives a modified
  // energy H̃ = H + O(h) that the scheme conserves, so H oscillates about a level with no
  // secular term. A drift of d per 4e4 steps would move the window means by d while widening
  // each window's range by d; asserted: the mean over the last 4e4 steps differs from the mean
  // over the 4e4 before by less than ¼ of the earlier window's range. (The range itself is not
  // compared across windows: it grows for ~2e5 steps while the release's energy spreads into
  // higher modes, whose O(h ω) error is larger — a redistribution, not a drift; over 1e6 steps
  // the range rises to ~3e-2 while the window means stay within 5e-4 of E0.)
  test::ThreadSpec spec;
  spec.control_points = 10;
  spec.integrator = {{"type", "SymplecticEuler"}};
  spec.dt = 2e-5;
  auto scene = test::loadThreadWith(spec, json::array({{{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 1e6}},
                                                       {{"type", "ParametricBending"}, {"youngs_modulus", 1e6}},
                                                       {{"type", "FixedPointConstraint"}, {"abscissa", 0.0}}}));
  const double omega_max = test::stiffestFrequency(*scene, scene->state());
  std::printf("  omega_max = %.3e rad/s, omega_max dt = %.3f\n", omega_max, omega_max * spec.dt);
  ASSERT_LT(omega_max * spec.dt, 0.5);
  const double scale = spec.mass * 9.81 * spec.length;  // energy exchanged in a swing (J)
  const double e0 = scene->energy(scene->state()).total();
  constexpr int kSteps = 100000, kSettle = 20000, kMiddle = 60000;
  // The error builds up over the first swings as energy spreads to higher modes; boundedness
  // is then judged on steps 2e4..6e4 against 6e4..1e5.
  double lo = e0, hi = e0, middle_lo = 1e300, middle_hi = -1e300, middle_sum = 0.0, late_sum = 0.0;
  for (int k = 1; k <= kSteps; ++k) {
    ASSERT_TRUE(scene->step().ok) << "step " << k;
    const double e = scene->energy(scene->state()).total();
    lo = std::min(lo, e);
    hi = std::max(hi, e);
    if (k > kSettle && k <= kMiddle) middle_lo = std::min(middle_lo, e), middle_hi = std::max(middle_hi, e), middle_sum += e - e0;
    if (k > kMiddle) late_sum += e - e0;
  }
  const double relative = (hi - lo) / scale;
  const double middle_mean = middle_sum / (kMiddle - kSettle), late_mean = late_sum / (kSteps - kMiddle);
  std::printf("  symplectic Euler, 1e5 steps of %.0e s: energy oscillation (max - min)/(m g L) = %.3e over the run, "
              "%.3e over steps 2e4..6e4; mean E - E0 over 2e4..6e4 %.3e, over 6e4..1e5 %.3e (relative to m g L)\n",
              spec.dt, relative, (middle_hi - middle_lo) / scale, middle_mean / scale, late_mean / scale);
  EXPECT_LT(relative, 0.1);
  EXPECT_LT(std::abs(late_mean - middle_mean), 0.25 * (middle_hi - middle_lo)) << "the energy drifts";
}

TEST(EnergyBehaviour, ImplicitEulerNeverIncreasesTheEnergyOfATautString) {
  // Taut string (1 % prestrain, both ends fixed) plus quadratic bending, plucked in modes 1 and 3
  // (amplitude 1 mm), no gravity, no damping; steps far beyond any explicit limit (ω_max h ≫ 1).
  // Round-off: the energy is dominated by the prestress ½ E A ε² L ≈ 3.1e-4 J (ε = 0.01). Positions
  // carry round-off ε_mach |q| ≈ 1e-17 m, which changes the strain of a 3 mm piece by 3e-15 and
  // the prestress energy by 2 δε/ε ≈ 6e-13 of itself. A rise above 1e-11 of the start energy
  // (3.4e-15 J, 1e-10 of the 2.6e-5 J of vibration) would be real.
  validation::TautString::Options options;
  options.amplitude = 1e-3;
  const validation::TautString problem(options);
  for (double dt : {1e-5, 1e-4, 1e-3}) {
    validation::RunSettings settings;
    settings.control_points = 30;
    settings.dt = dt;
    settings.integrator = {{"type", "ImplicitEuler"}};
    json document = problem.scene(settings);
    document["nodes"][0]["components"].push_back({{"type", "ParametricBending"}, {"youngs_modulus", 2e9}});
    static const Factory factory = app::makeFactory();
    auto scene = loadScene(document, "taut string with bending", factory);
    problem.prepare(*scene);
    SceneState s = scene->state();  // add mode 3 to mode 1 (a smooth shape with zero end values)
    const auto& q0 = scene->bodies().front()->initialPositions();
    for (int i = 0; i < q0.rows(); ++i) s.q[3 * i + 2] = 0.5 * s.q[3 * i + 1] * std::cos(2.0 * 3.14159265 * q0(i, 0) / 0.1);
    scene->setState(s);
    const double start = scene->energy(scene->state()).total();
    double previous = start, worst_rise = -1e300;
    for (int k = 0; k < 300; ++k) {
      const StepReport report = scene->step();
      ASSERT_TRUE(report.ok) << report.message;
      const double e = scene->energy(scene->state()).total();
      worst_rise = std::max(worst_rise, e - previous);
      previous = e;
    }
    std::printf("  implicit Euler, dt = %.0e s: energy %.6e -> %.6e J over 300 steps, largest one-step change %+.2e J\n",
                dt, start, previous, worst_rise);
    EXPECT_LE(worst_rise, 1e-11 * start) << "dt = " << dt;
    EXPECT_LT(previous, start);
  }
}

}  // namespace
}  // namespace filum
