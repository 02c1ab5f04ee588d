// Integrator orders on a smooth problem: measured global order ≈ 1 for explicit,
// symplectic and implicit Euler, 2 for the implicit midpoint rule, 4 for RK4.
//
// Problem: a free soft thread (no constraint: the Baumgarte rate ω = 0.1/dt would change the ODE
// with dt), 6 control points, 10 cm, E = 20 kPa (GreenLagrangeStretching and ParametricBending),
// light viscous damping, gravity, released at rest from a curved, 2 % stretched shape, run to
// T = 10 ms. Its stiffest mode has ω_max ≈ 1.1e3 rad/s (linearized eigenvalues, checked below).
// Asymptotic range. A method of order p has error C h^p (1 + O(ω h)), but a first-order method
// also changes the stiffest mode's amplitude by a factor exp(± h ω_max² T / 2), which is linear in
// h only while h ω_max² T / 2 ≪ 1, i.e. h ≪ 1.5e-4 s here. So the first-order methods run at
// T/2048 .. T/16384 (h ω_max² T / 2 <= 0.03), the others at T/64 .. T/512 (ω_max h <= 0.18).
// Error: max |q(T) − q_ref(T)| with q_ref from RK4 at T/32768 (its own error, C h⁴, is below
// 1e-16 m, far under every error fitted).
// Order: least-squares slope of log error against log dt over the four steps of each method,
// asserted within ±0.15 of p (the O(ω h) and O(h ω² T) corrections at the coarsest step).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/mechanics_scenes.hpp"

namespace filum {
namespace {

using nlohmann::json;

constexpr double kDuration = 0.01;  // s

std::unique_ptr<Scene> smoothProblem(const json& integrator, double dt) {
  test::ThreadSpec spec;
  spec.control_points = 6;
  spec.integrator = integrator;
  spec.dt = dt;
  auto scene = test::loadThreadWith(spec, json::array({{{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e4}},
                                                       {{"type", "ParametricBending"}, {"youngs_modulus", 2e4}},
                                                       {{"type", "ViscousDamping"}, {"coefficient", 5.0}}}));
  // Curved and stretched: x stretched by 2 %, a smooth bump in y and z.
  SceneState s = scene->state();
  for (int i = 0; i < scene->dofPointCount(); ++i) {
    const double x = s.q[3 * i];
    s.q[3 * i] = 1.02 * x;
    s.q[3 * i + 1] = 0.01 * std::sin(30.0 * x);
    s.q[3 * i + 2] = 0.005 * std::cos(20.0 * x);
  }
  scene->setState(s);
  return scene;
}

VecX finalPositions(const json& integrator, int steps) {
  auto scene = smoothProblem(integrator, kDuration / steps);
  for (int k = 0; k < steps; ++k) {
    const StepReport report = scene->step();
    EXPECT_TRUE(report.ok) << report.message;
  }
  return scene->state().q;
}

TEST(IntegratorOrder, MeasuredOrdersAreOneTwoAndFour) {
  // The premise: ω_max h <= 0.4 at the coarsest step (eigenvalues of M⁻¹K at the start).
  {
    auto scene = smoothProblem({{"type", "RungeKutta4"}}, 1e-4);
    const double omega_max = test::stiffestFrequency(*scene, scene->state());
    std::printf("  omega_max = %.3e rad/s: omega_max h at T/64 = %.3f, h omega_max^2 T / 2 at T/2048 = %.3f\n", omega_max,
                omega_max * kDuration / 64, kDuration / 2048 * omega_max * omega_max * kDuration / 2);
    ASSERT_LE(omega_max * kDuration / 64, 0.2);
    ASSERT_LE(kDuration / 2048 * omega_max * omega_max * kDuration / 2, 0.05);
  }
  const VecX reference = finalPositions({{"type", "RungeKutta4"}}, 32768);

  struct Case {
    const char* type;
    double order;
    int coarsest;  // steps of the coarsest run; then twice, 4 and 8 times as many
  };
  for (const Case& c : {Case{"ExplicitEuler", 1, 2048}, Case{"SymplecticEuler", 1, 2048}, Case{"ImplicitEuler", 1, 2048},
                        Case{"ImplicitMidpoint", 2, 64}, Case{"RungeKutta4", 4, 64}}) {
    json integrator = {{"type", c.type}};
    if (std::string(c.type).rfind("Implicit", 0) == 0) {
      integrator["solve"] = "newton";  // the order of the scheme itself, not of its linearization
      integrator["newton_tolerance"] = 1e-13;
    }
    std::vector<double> log_h, log_e;
    std::printf("  %-16s", c.type);
    for (int steps : {c.coarsest, 2 * c.coarsest, 4 * c.coarsest, 8 * c.coarsest}) {
      const double error = (finalPositions(integrator, steps) - reference).lpNorm<Eigen::Infinity>();
      log_h.push_back(std::log(kDuration / steps));
      log_e.push_back(std::log(error));
      std::printf(" T/%-5d %.3e m ", steps, error);
    }
    // Least-squares slope of log e against log h.
    const double mh = (log_h[0] + log_h[1] + log_h[2] + log_h[3]) / 4, me = (log_e[0] + log_e[1] + log_e[2] + log_e[3]) / 4;
    double sxy = 0, sxx = 0;
    for (int k = 0; k < 4; ++k) {
      sxy += (log_h[k] - mh) * (log_e[k] - me);
      sxx += (log_h[k] - mh) * (log_h[k] - mh);
    }
    const double slope = sxy / sxx;
    std::printf(" -> order %.3f\n", slope);
    EXPECT_NEAR(slope, c.order, 0.15) << c.type;
  }
}

}  // namespace
}  // namespace filum
