// The capstan with the cord's own weight (capstan_scene.hpp): a silicone cord over a fixed peg
// holds when its heavy arm is shorter than the capstan limit L2_max and slips when it is longer,
// at two coefficients of friction; while held it does not creep.
//
// The limit is computed independently of the simulation: in closed form (capstanHeaviestArm) and,
// as a check of that derivation, by integrating dT/dθ = μT + wρ_c(cos θ + μ sin θ) with RK4.
//
// Tolerances.
//  - Slip at 1.02 of L2_max (a 2 % margin); hold at 0.95: the discretization's first-order
//    deficit (kHeld below). What else moves the true threshold away from the ideal capstan, and
//    is left out: the cord's bending stiffness concentrates normal force where it enters
//    and leaves the peg (a moment EI/ρ_c over the boundary layer ℓ = √(EI/T)), which adds friction
//    of relative size about 2μℓ/ρ_c: with EI = 7.9e-10 N·m², T >= 8.5e-3 N, ℓ <= 0.3 mm, ρ_c = 31 mm,
//    at most 0.8 % at μ = 0.4; the cord's stretch (T/EA <= 1 %) moves mass between the wrap and the
//    arms by at most 1 % of the wrap's weight term, itself 6 % of L2_max: 0.06 %. Both well inside 2 %.
//  - No creep while held: after the settling pin is released (capstan_scene.hpp), the material
//    point on top of the peg moves slower than 0.01 mm/s over the last second (the bound asked of
//    held contacts; exact Coulomb stick has no creep at all, the friction rows' compliance allows
//    R λ_t/ω_f, about 1e-7 m/s here, and the arms' remaining waves are damped at 5 /s).
//  - Slip: above the limit the cord runs off towards the heavy side, faster and faster (every mm
//    slipped makes the heavy arm heavier); at 1.02 L2_max the excess weight, 2 % of w L2,
//    accelerates the cord's mass w(L1 + πρ_c + L2)/g at about 0.1 m/s², slowed by the 5 /s damping
//    to about 2 cm/s: over the 2 s after the release the top point moves several cm. 5 mm is asked.
#include <cmath>

#include <gtest/gtest.h>

#include "capstan_scene.hpp"
#include "collision_scenes.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/geometry/spline_curve.hpp"

namespace filum::collision {
namespace {

/// RK4 of dT/dθ = μT + wρ(cos θ + μ sin θ), T(0) = w L1, over [0, π]: T(π)/w.
double integratedHeaviestArm(double mu, double light_arm, double rho) {
  auto f = [&](double theta, double t) { return mu * t + rho * (std::cos(theta) + mu * std::sin(theta)); };
  const int n = 2000;
  const double h = M_PI / n;
  double t = light_arm;
  for (int i = 0; i < n; ++i) {
    const double theta = i * h;
    const double k1 = f(theta, t), k2 = f(theta + h / 2, t + h / 2 * k1), k3 = f(theta + h / 2, t + h / 2 * k2),
                 k4 = f(theta + h, t + h * k3);
    t += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return t;
}

TEST(Capstan, ClosedFormAgreesWithTheIntegratedEquation) {
  // RK4's global error is O(h⁴): with h = π/2000 and derivatives of order e^{μπ}, about 1e-13
  // relative; 1e-10 leaves room for the round-off of 2000 steps.
  for (double mu : {0.0, 0.2, 0.4, 1.0})
    for (double l1 : {0.1, 0.25}) {
      const double closed = test::capstanHeaviestArm(mu, l1, 0.031);
      EXPECT_NEAR(closed, integratedHeaviestArm(mu, l1, 0.031), 1e-10 * closed) << "mu " << mu;
    }
  // Without friction the peg holds only equal arms (the wrap's weight term vanishes with μ).
  EXPECT_DOUBLE_EQ(test::capstanHeaviestArm(0.0, 0.25, 0.031), 0.25);
}

struct CapstanRun {
  double top_moved = 0.0;  // displacement of the material point on top of the peg since its release (m)
  double creep = 0.0;      // its mean speed over the second half of the time since (m/s)
  std::string failure;
};

CapstanRun runCapstan(double mu, double heavy_fraction) {
  test::CapstanCord cord;
  cord.friction = mu;
  cord.heavy_arm = heavy_fraction * test::capstanHeaviestArm(mu, cord.light_arm, cord.wrapRadius());
  auto scene = test::loadCollisionScene(test::capstanScene(cord));
  scene->init();
  const double s_top = test::capstanTopAbscissa(cord);
  auto top = [&] {
    const auto& body = *scene->bodies()[0]->curve();
    return geometry::curvePoint(body.basis(), body.block(scene->state().q), s_top);
  };
  const long steps = std::lround(cord.duration / cord.dt), released = std::lround(cord.settle / cord.dt);
  const long half = (steps + released) / 2;
  Vec3 start = top(), middle = start;
  CapstanRun run;
  for (long k = 1; k <= steps; ++k) {
    const StepReport report = scene->step();
    if (!report.ok) {
      run.failure = report.message;
      return run;
    }
    if (k == released) start = top();
    if (k == half) middle = top();
  }
  const Vec3 end = top();
  run.top_moved = (end - start).norm();
  run.creep = (end - middle).norm() / ((steps - half) * cord.dt);
  return run;
}

// The discrete cord holds less than the continuous capstan: the deficit is first order in the
// control-point spacing h (measured with the Newton solve and with projected Gauss–Seidel alike,
// with and without bending stiffness: the cord slides at 0.96 of L2_max and holds at 0.93 with
// h = 10 mm, slides at 0.99 and holds at 0.96 with h = 5 mm; with dt = 0.25 ms as with 1 ms). At
// h = 5 mm the threshold is thus about 0.975; "held" is asked at 0.95, twice that deficit below
// the limit. Holding at 2 % below the limit would need h <= 2.5 mm.
constexpr double kHeld = 0.95;

class CapstanLimit : public ::testing::TestWithParam<double> {};

TEST_P(CapstanLimit, HoldsBelowWithoutCreep) {
  const CapstanRun run = runCapstan(GetParam(), kHeld);
  ASSERT_TRUE(run.failure.empty()) << run.failure;
  EXPECT_LT(run.creep, 1e-5) << "moved " << run.top_moved << " m";
}

TEST_P(CapstanLimit, SlipsAbove) {
  const CapstanRun run = runCapstan(GetParam(), 1.02);
  ASSERT_TRUE(run.failure.empty()) << run.failure;
  EXPECT_GT(run.top_moved, 5e-3);
}

INSTANTIATE_TEST_SUITE_P(Friction, CapstanLimit, ::testing::Values(0.2, 0.4));

}  // namespace
}  // namespace filum::collision
