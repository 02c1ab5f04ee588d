// Contact from inside a vessel lumen (VesselLumenObstacle) in the one constraint solver: a rod
// lying in an inclined straight tube slides down it with Coulomb's acceleration g (sin α − μ cos α)
// or, when tan α < μ, stays put; it never sinks into the wall by more than a tenth of its radius,
// and every contact force lies in its friction cone. And what the obstacle refuses.
#include <cmath>

#include <gtest/gtest.h>

#include "collision_scenes.hpp"
#include "inclined_tube_slide.hpp"
#include "filum/collision/vessel_lumen_obstacle.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::collision {
namespace {

constexpr double kTube = 5e-3;   // m, lumen radius
constexpr double kRod = test::kSlideRodRadius;
constexpr double kG = test::kSlideGravity;

struct SlideRun {
  double displacement = 0.0;      // m, of the rod's middle along the tube's axis (down the slope: > 0)
  double worst_penetration = 0.0; // m, deepest a point of the rod's centre line came within r of the wall
  double worst_cone = 0.0;        // max over contacts of |F_t| − μ F_n (N)
  double largest_force = 0.0;     // N
};

SlideRun slide(double alpha, double mu, double duration) {
  SlideRun run;
  const auto lumen = [](const test::InclinedTube& tube) {
    const Vec3 a = -0.15 * tube.axis, b = 0.15 * tube.axis;
    return nlohmann::json{{"type", "VesselLumenObstacle"},
                          {"branches",
                           {{{"name", "tube"},
                             {"open", {"start", "end"}},
                             {"points", {{a.x(), a.y(), a.z(), kTube}, {b.x(), b.y(), b.z(), kTube}}}}}}};
  };
  run.displacement = test::slideDownInclinedTube(alpha, mu, duration, kTube, lumen, [&](const Scene& scene) {
    const CurveBody& rod = *scene.bodies()[0]->curve();
    const auto& vessel = dynamic_cast<const VesselLumenObstacle&>(*test::pipelineOf(scene).obstacles()[0]);
    for (int i = 0; i <= 50; ++i) {
      const Vec3 x = rod.position(scene.state().q, i / 50.0);
      const geometry::VesselTree::Sample s = vessel.tree().sample(x, kTube);
      run.worst_penetration = std::max(run.worst_penetration, kRod - s.value / s.gradient.norm());
    }
    const ContactPipeline& pipeline = test::pipelineOf(scene);
    for (int c = 0; c < static_cast<int>(pipeline.contacts().size()); ++c) {
      const Vec3 f = pipeline.contactForce(c, scene.state());
      const Vec3 n = pipeline.contacts()[c].normal;
      const double fn = f.dot(n);
      run.worst_cone = std::max(run.worst_cone, (f - fn * n).norm() - mu * fn);
      run.largest_force = std::max(run.largest_force, f.norm());
    }
  });
  return run;
}

TEST(VesselLumen, RodSlidesDownAnInclinedTubeWithCoulombsAcceleration) {
  // α = 30°, μ = 0.3: a = g (sin α − μ cos α) = 2.356 m/s², d = ½ a t² after t = 0.2 s. Implicit
  // Euler's positions under a constant acceleration are a h² n(n + 1)/2: 1/n = 0.5 % long after
  // n = 200 steps; a start one step late (the contact rows' first step) would make it 2h/t = 1 %
  // short: within [−1 %, +0.5 %], asked within 1.5 %.
  const double alpha = M_PI / 6, mu = 0.3, t = 0.2;
  const SlideRun run = slide(alpha, mu, t);
  const double expected = 0.5 * kG * (std::sin(alpha) - mu * std::cos(alpha)) * t * t;
  std::printf("  slid %.3f mm, Coulomb %.3f mm; deepest %.4f of r; cone excess %.2e N\n", 1e3 * run.displacement,
              1e3 * expected, run.worst_penetration / kRod, run.worst_cone);
  EXPECT_NEAR(run.displacement, expected, 0.015 * expected);
  EXPECT_LT(run.worst_penetration, 0.1 * kRod);
  // In the cone to the solver's tolerance: its residual is 1e-6 of the largest term it balances, as
  // an acceleration; ρ_t = 2/(W_t1t1 + W_t2t2) turns it into a force, and the rows' W_rr differ by
  // a few times along the rod: 1e-5 of the largest force.
  EXPECT_LT(run.worst_cone, 1e-5 * run.largest_force);
}

TEST(VesselLumen, RodHeldByFrictionWhenTheSlopeIsBelowTheAngleOfFriction) {
  // tan 30° = 0.577 < μ = 0.7: static; the compliance of the friction rows (R λ_t / ω_f) lets it
  // creep by less than a µm over the run (docs/contact-solver.md), we ask less than 10 µm.
  const double alpha = M_PI / 6, mu = 0.7;
  const SlideRun run = slide(alpha, mu, 0.2);
  std::printf("  moved %.4f mm\n", 1e3 * run.displacement);
  EXPECT_LT(std::abs(run.displacement), 1e-5);
  EXPECT_LT(run.worst_penetration, 0.1 * kRod);
  EXPECT_LT(run.worst_cone, 1e-5 * run.largest_force);
}

TEST(VesselLumen, ObstacleRefusesWrongUnitsAndMissingFiles) {
  auto refused = [](const nlohmann::json& component, const std::string& expected) {
    const nlohmann::json document = {
        {"dt", 1e-3},
        {"nodes", {{{"name", "vessel"}, {"components", {component}}}}}};
    try {
      test::loadCollisionScene(document);
      ADD_FAILURE() << "accepted: " << component.dump();
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  // A lumen in mm read as metres: a radius of 10 m.
  refused({{"type", "VesselLumenObstacle"}, {"branches", {{{"points", {{0, 0, 0, 10}, {0, 0, 50, 10}}}}}}},
          "\"units\": \"mm\"");
  // One in metres read as mm: 10 µm.
  refused({{"type", "VesselLumenObstacle"}, {"units", "mm"}, {"branches", {{{"points", {{0, 0, 0, 0.01}, {0, 0, 0.05, 0.01}}}}}}},
          "\"units\": \"m\"");
  refused({{"type", "VesselLumenObstacle"}, {"file", "no_such_tree.json"}}, "no such file");
  refused({{"type", "VesselLumenObstacle"}}, "/nodes/0/components/0/file");
}

}  // namespace
}  // namespace filum::collision
