// Catenary (validation against analytic physics): a 10 cm 3-0 polypropylene suture
// (E = 2 GPa, r = 0.1 mm, ρ = 910 kg/m³, GreenLagrangeStretching, no bending) hangs between two
// fixed points 8 cm apart and comes to rest on z = a cosh((x − S/2)/a) + c, 2a sinh(S/2a) = L
// (apps/validation/catenary.hpp). Implicit Euler, dt = 5 ms, strong viscous damping
// (γ = 30/s, near-critical for the slowest swing), 2 s: the kinetic energy is then ~1e-30 J and
// what remains is the equilibrium's error.
//
// What the mathematics says about the error e(n) (max distance of P(s) to the analytic curve):
//  - a floor of O(L ε) ≈ 2e-8 m from the thread's extensibility (ε = T/EA ≈ 3e-7), which the
//    inextensible analytic curve ignores;
//  - above it, spline discretization: a cubic spline approximates the curve to O(h⁴) at best,
//    and the stiff stretching energy locks (exact |P'| at 5 Gauss nodes per piece cannot hold
//    on a curved cubic piece) until h is small enough; so doubling n must divide the error by
//    at least 2⁴ = 16 once locking fades (measured: ≈ 2⁶).
// Asserted: e decreases with n from n = 30; e(40)/e(80) >= 16 and e(30)/e(60) >= 16; e(30) below
// 2e-4 m (0.2 % of the length; measured 9e-5 m); e(80) below 1e-6 m (measured 3e-7 m); and the
// constraints hold (violation < 1e-12 m).
#include <gtest/gtest.h>

#include <cstdio>
#include <map>

#include "filum/mechanics/implicit_euler.hpp"
#include "validation/catenary.hpp"

namespace filum {
namespace {

TEST(CatenaryValidation, ThreadComesToRestOnTheCatenaryAndConvergesWithN) {
  const validation::Catenary problem;
  validation::RunSettings settings;
  settings.integrator = {{"type", "ImplicitEuler"}};  // linearized, with its error estimate (the default)
  settings.dt = 5e-3;
  std::printf("  catenary: L = %.3f m, S = %.3f m, a = %.6f m\n", problem.options().length, problem.options().span,
              problem.parameter());
  std::map<int, double> error;
  for (int n : {20, 30, 40, 60, 80}) {
    settings.control_points = n;
    auto scene = validation::loadProblem(problem, settings);
    std::string failure;
    ASSERT_TRUE(validation::advance(*scene, problem.duration(), &failure)) << "n = " << n << ": " << failure;
    error[n] = problem.error(*scene);
    const double kinetic = scene->energy(scene->state()).kinetic;
    const double violation = scene->constraintViolation(scene->state()).cwiseAbs().maxCoeff();
    const auto& solver = dynamic_cast<const mechanics::ImplicitEuler&>(scene->integrator()).solver();
    std::printf("  n = %3d: max distance %.3e m, kinetic %.1e J, violation %.1e m, %ld Newton iterations, %ld halvings\n",
                n, error[n], kinetic, violation, solver.totalIterations(), solver.halvings());
    EXPECT_LT(kinetic, 1e-20) << "n = " << n << " is not at rest";
    EXPECT_LT(violation, 1e-12) << "n = " << n;
  }
  EXPECT_LT(error[40], error[30]);
  EXPECT_LT(error[60], error[40]);
  EXPECT_LT(error[80], error[60]);
  EXPECT_GE(error[30] / error[60], 16.0) << "slower than the O(h⁴) of cubic splines";
  EXPECT_GE(error[40] / error[80], 16.0) << "slower than the O(h⁴) of cubic splines";
  EXPECT_LT(error[30], 2e-4);
  EXPECT_LT(error[80], 1e-6);
}

TEST(CatenaryValidation, StepsAHundredTimesLongerHalveThroughTheStartAndEndOnTheSameCurve) {
  // catenary.json's settings (Newton to 1e-10, 10 iterations, up to 16 halvings, n = 30) at
  // dt × 100 = 0.5 s. The stiff string's first steps are a strain transient of microseconds (its
  // stiffest mode has a period of 2.3 µs; the initial arc's moved end points are strained): Newton
  // converges there only in sub-steps of ~15 µs, 2^15 below 0.5 s, and then climbs back to whole
  // steps; the step's budget of Newton solves bounds its work (implicit_step_solver.hpp).
  // At rest, a backward Euler step's fixed point is the static equilibrium whatever h, so the
  // thread ends on the curve the 5 ms steps reach: the same bound on the distance, 2e-4 m
  // (measured 9e-5 m at n = 30; the difference between the two runs is Newton's tolerance).
  const validation::Catenary problem;
  validation::RunSettings settings;
  settings.integrator = {{"type", "ImplicitEuler"}, {"solve", "newton"}, {"newton_iterations", 10}, {"newton_tolerance", 1e-10},
                         {"max_halvings", 16}};
  settings.dt = 0.5;
  settings.control_points = 30;
  auto scene = validation::loadProblem(problem, settings);
  std::string failure;
  ASSERT_TRUE(validation::advance(*scene, problem.duration(), &failure)) << failure;
  const auto& solver = dynamic_cast<const mechanics::ImplicitEuler&>(scene->integrator()).solver();
  std::printf("  dt = 0.5 s: max distance %.3e m, %ld Newton solves (attempts), %ld halvings\n", problem.error(*scene),
              solver.solves(), solver.halvings());
  EXPECT_LT(problem.error(*scene), 2e-4);
  EXPECT_LT(scene->energy(scene->state()).kinetic, 1e-20);

  // Halving no deeper than 10 (the default: sub-steps of 0.49 ms), the start is not got through:
  // the first step is refused at that depth.
  settings.integrator.erase("max_halvings");
  scene = validation::loadProblem(problem, settings);
  EXPECT_FALSE(validation::advance(*scene, problem.duration(), &failure));
  EXPECT_NE(failure.find("max_halvings 10 reached"), std::string::npos) << failure;

  // With 16 levels but a budget of 15 Newton solves for the step, the start cannot be reached:
  // the step is refused, and the message says which limit stopped it.
  settings.integrator["max_halvings"] = 16;
  settings.integrator["max_step_solves"] = 15;
  scene = validation::loadProblem(problem, settings);
  EXPECT_FALSE(validation::advance(*scene, problem.duration(), &failure));
  EXPECT_NE(failure.find("max_step_solves 15 reached"), std::string::npos) << failure;
}

}  // namespace
}  // namespace filum
