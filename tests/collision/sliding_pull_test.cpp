// Sliding that survives: the capstan cord (capstan_scene.hpp, μ = 0.3 on the peg) held by its
// light end, which a scripted grip pulls down and lets back up at 1 m/s (a triangle wave of
// 0.15 m every 0.15 s) for 2 s, while the heavy arm runs through a sliding point (a hole with
// friction) below the peg. Implicit Euler at 1 ms: the cord slides over the peg and through the
// hole at up to 1 m/s each way. Asked: every step succeeds, the state stays finite, and the cord
// really slides over the peg (the material point that starts on top travels more than 0.1 m).
#include <cmath>

#include <gtest/gtest.h>

#include "capstan_scene.hpp"
#include "collision_scenes.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/geometry/spline_curve.hpp"

namespace filum::collision {
namespace {

TEST(SlidingPull, ACordPulledOverAPegAndThroughAHoleAtOneMetrePerSecondDoesNotDiverge) {
  test::CapstanCord cord;
  cord.bending_modulus = cord.youngs_modulus;  // the solid cord (capstan_scene.hpp) this test was written for
  cord.heavy_arm = 0.5;  // below the capstan limit (0.70 m at μ = 0.3): held when the grip stops
  nlohmann::json document = test::capstanScene(cord);
  auto& components = document["nodes"][0]["components"];
  // Drop the settling pin (the grip holds the light end from the start); add the grip on the light end (s = 0, at (ρ_c, 0, −L1)) and the hole.
  components.erase(components.end() - 1);
  const double x = cord.wrapRadius(), z0 = -cord.light_arm;
  nlohmann::json path = nlohmann::json::array();
  const double period = 0.15, depth = 0.15;  // 1 m/s each way
  for (int k = 0; k * period <= 2.0 + 1e-9; ++k)
    path.push_back({{"time", k * period}, {"position", {x, 0.0, k % 2 ? z0 - depth : z0}}});
  components.push_back({{"type", "FixedPointConstraint"}, {"name", "grip"}, {"abscissa", 0.0}, {"path", path}});
  const double length = cord.light_arm + M_PI * cord.wrapRadius() + cord.heavy_arm;
  const double hole = (cord.light_arm + M_PI * cord.wrapRadius() + 0.2) / length;  // 0.2 m down the heavy arm
  components.push_back({{"type", "SlidingPointConstraint"}, {"name", "hole"}, {"abscissa", hole}, {"friction", 1e-3}});
  document["duration"] = 2.0;

  auto scene = test::loadCollisionScene(document);
  scene->init();
  const double s_top = test::capstanTopAbscissa(cord);
  auto top = [&] {
    const auto& body = *scene->bodies()[0]->curve();
    return geometry::curvePoint(body.basis(), body.block(scene->state().q), s_top);
  };
  const Vec3 start = top();
  double travelled = 0.0;
  const long steps = std::lround(2.0 / cord.dt);
  for (long k = 1; k <= steps; ++k) {
    const StepReport report = scene->step();
    ASSERT_TRUE(report.ok) << "step " << k << ": " << report.message;
    ASSERT_TRUE(scene->state().q.allFinite());
    travelled = std::max(travelled, (top() - start).norm());
  }
  const ContactSolveTally& tally = scene->constraintSolver()->contactTally();
  std::printf("  top point travelled up to %.3f m; %ld contact solves, %.1f %% converged, %ld halvings\n", travelled,
              tally.solves, 100.0 * tally.converged / std::max(1L, tally.solves), scene->solveHalvings());
  EXPECT_GT(travelled, 0.1);
}

}  // namespace
}  // namespace filum::collision
