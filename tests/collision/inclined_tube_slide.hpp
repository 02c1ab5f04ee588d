// The lumen tests' shared scene: a rod lying along the bottom line of a tube inclined at α, under
// gravity, with Coulomb friction μ against the tube's wall (whatever obstacle makes the tube: a
// centreline lumen, a segmented mesh). It slides with a = g (sin α − μ cos α) when tan α > μ and
// stays put otherwise: the reference the contact from inside a lumen is checked against.
#pragma once

#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "collision_scenes.hpp"
#include "filum/core/curve_body.hpp"

namespace filum::test {

constexpr double kSlideRodRadius = 5e-4;  // m
constexpr double kSlideRodLength = 0.05;  // m
constexpr double kSlideGravity = 9.81;    // m/s²

struct InclinedTube {
  Vec3 axis, down;  // the tube's axis (uphill) and, across it, the direction of its bottom line
};

/// Runs the rod for `duration` at 1 ms (implicit Euler) in a tube inclined at α whose bottom line
/// lies `bottom` from the axis, made by the obstacle component `lumen(tube)`, with friction μ;
/// `each_step(scene)` after every step. Returns the displacement of the rod's middle down the slope.
inline double slideDownInclinedTube(double alpha, double mu, double duration, double bottom,
                                    const std::function<nlohmann::json(const InclinedTube&)>& lumen,
                                    const std::function<void(const Scene&)>& each_step) {
  const InclinedTube tube{Vec3(std::cos(alpha), 0, std::sin(alpha)), Vec3(std::sin(alpha), 0, -std::cos(alpha))};
  const Vec3 start = (bottom - kSlideRodRadius) * tube.down - 0.5 * kSlideRodLength * tube.axis;
  const Vec3 end = start + kSlideRodLength * tube.axis;
  nlohmann::json obstacle = lumen(tube);
  obstacle["friction"] = mu;
  const nlohmann::json document = {
      {"dt", 1e-3},
      {"duration", duration},
      {"gravity", {0, 0, -kSlideGravity}},
      {"integrator", {{"type", "ImplicitEuler"}}},
      {"constraint_solver", {{"type", "LagrangeMultiplierSolver"}}},
      {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"friction", mu}}},
      {"nodes",
       {{{"name", "vessel"}, {"components", {obstacle}}},
        {{"name", "rod"},
         {"components",
          {{{"type", "FramedChain"},
            {"nodes", {{"from", {start.x(), start.y(), start.z()}}, {"to", {end.x(), end.y(), end.z()}}, {"count", 11}}},
            {"radius", kSlideRodRadius},
            {"density", 1150}},
           {{"type", "ChainElasticity"}, {"youngs_modulus", 3e7}, {"poisson_ratio", 0.5}},
           {{"type", "SphereCollisionModel"}, {"spacing", 8e-4}}}}}}}};
  auto scene = loadCollisionScene(document);
  scene->init();
  const CurveBody& rod = *scene->bodies()[0]->curve();
  const Vec3 middle0 = rod.position(scene->state().q, 0.5);
  const long steps = std::lround(duration / 1e-3);
  for (long k = 0; k < steps; ++k) {
    const StepReport report = scene->step();
    EXPECT_TRUE(report.ok) << report.message;
    if (!report.ok) break;
    each_step(*scene);
  }
  return -(rod.position(scene->state().q, 0.5) - middle0).dot(tube.axis);
}

}  // namespace filum::test
