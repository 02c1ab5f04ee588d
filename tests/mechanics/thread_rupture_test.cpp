// A thread tears at the tension its material bears (GreenLagrangeStretching "break_force",
// ForceField::tearsAt, Scene::applyRuptures), not before: a 10 cm 3-0 silk thread held at one end
// and drawn out slowly at the other tears at the step at which the Green–Lagrange tension of the
// imposed stretch reaches the break force, and is cut there (two strands).
#include <gtest/gtest.h>

#include <cmath>

#include "filum/all_components.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_loader.hpp"

namespace filum {
namespace {

using nlohmann::json;

TEST(ThreadRupture, TearsAtTheStatedTensionNotBefore) {
  // Silk 3-0: r = 0.11 mm, E = 8.7 GPa, E A = 330.7 N; break force 5 N (far below silk's real
  // strength, about 400 MPa · A = 15 N, to keep the test short). The far end is drawn along +x at
  // v = 2 mm/s (a linear path): the stretch λ(t) = 1 + v t / L is uniform along the thread (the
  // axial wave crosses it in L / sqrt(E/ρ) = 39 µs, 25 times per step), and the Green–Lagrange
  // tension is N = E A (λ² − 1)/2 · λ (green_lagrange_stretching.hpp).
  constexpr double L = 0.1, r = 1.1e-4, E = 8.7e9, v = 2e-3, h = 1e-3, F = 5.0;
  const double EA = E * M_PI * r * r;
  const json points = {{"from", {0, 0, 0}}, {"to", {L, 0, 0}}, {"count", 30}};
  const json components = json::array(
      {{{"type", "DynamicSpline"}, {"control_points", points}, {"radius", r}, {"density", 1300}},
       {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", E}, {"break_force", F}},
       {{"type", "CurvatureBending"}, {"youngs_modulus", 5e8}},
       {{"type", "FixedPointConstraint"}, {"abscissa", 0.0}},
       {{"type", "FixedPointConstraint"}, {"abscissa", 1.0},
        {"path", json::array({{{"time", 0.0}, {"position", {L, 0, 0}}}, {{"time", 1.0}, {"position", {L + v, 0, 0}}}})}}});
  const json document{{"name", "rupture"}, {"dt", h}, {"duration", 1.0}, {"gravity", {0, 0, 0}},
                      {"integrator", {{"type", "ImplicitEuler"}}},
                      {"nodes", json::array({{{"name", "thread"}, {"components", components}}})}};
  auto scene = loadScene(document, "rupture test", app::makeFactory());
  // The stretch at which N = F: λ³ − λ = 2F/(EA), by Newton from λ = 1 + F/EA.
  double lambda = 1.0 + F / EA;
  for (int it = 0; it < 20; ++it) lambda -= (lambda * lambda * lambda - lambda - 2 * F / EA) / (3 * lambda * lambda - 1);
  const double t_tear = (lambda - 1.0) * L / v;
  long torn_at = -1;
  for (long k = 0; k < 1000 && torn_at < 0; ++k) {
    ASSERT_TRUE(scene->step().ok) << "step " << k;
    if (!scene->ruptures().empty()) torn_at = k;
  }
  ASSERT_GE(torn_at, 0) << "never tore; expected at t = " << t_tear << " s";
  const Scene::Rupture& tear = scene->ruptures().front();
  // The tension is measured at the end of each step and the cut made at the start of the next:
  // the tear comes at the first step start t_k = k h with N(t_k) > F, so t_k − h < t_tear <= t_k.
  // The drawn end follows its path up to Baumgarte's correction, a lag far below one step's
  // travel v h: the tear lies within one step of t_tear.
  EXPECT_NEAR(tear.time, t_tear, 1.0 * h + 1e-12);
  EXPECT_GT(tear.tension, F);
  // One step of stretch adds dN/dλ · v h / L = E A (3λ² − 1)/2 · v h / L ≈ E A v h / L = 6.6e-3 N.
  EXPECT_LT(tear.tension, F + 2.0 * EA * v * h / L);
  EXPECT_GT(tear.abscissa, 0.0);
  EXPECT_LT(tear.abscissa, 1.0);
  EXPECT_EQ(strands(scene->bodies().front()->curve()->basis()).size(), 2u);
}

}  // namespace
}  // namespace filum
