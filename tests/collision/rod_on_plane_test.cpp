// A rod (FramedChain, segments of 2 cm) dropped onto a table through ~13 contact spheres per
// segment: the narrow phase keeps the two end contacts of each straight segment against the flat
// table (keepSpanEnds, narrow_phase.cpp) and the rod still rests on it with no sphere inside.
#include <gtest/gtest.h>

#include "filum/all_components.hpp"
#include "filum/collision/contact_pipeline.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"

namespace filum::collision {
namespace {

using nlohmann::json;

TEST(RodOnPlane, KeepsTwoContactsPerSegmentAndNoSphereSinks) {
  const double r = 1e-3;
  const json document = {
      {"dt", 1e-3},
      {"gravity", {0, 0, -9.81}},
      {"integrator", {{"type", "ImplicitEuler"}}},
      {"constraint_solver", {{"type", "LagrangeMultiplierSolver"}}},
      {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"friction", 0.3}}},
      {"nodes",
       {{{"name", "rod"},
         {"components",
          {{{"type", "FramedChain"}, {"nodes", {{"from", {0, 0, 1.5e-3}}, {"to", {0.2, 0, 1.5e-3}}, {"count", 11}}}, {"radius", r}, {"density", 1150}},
           {{"type", "ChainElasticity"}, {"youngs_modulus", 3e7}},
           {{"type", "ViscousDamping"}, {"coefficient", 5.0}},
           {{"type", "SphereCollisionModel"}, {"spacing", 1.5e-3}}}}},
        {{"name", "table"}, {"components", {{{"type", "PlaneObstacle"}, {"point", {0, 0, 0}}, {"normal", {0, 0, 1}}}}}}}}};
  auto scene = loadScene(document, "rod on a plane", app::makeFactory());
  scene->init();
  for (int k = 0; k < 500; ++k) ASSERT_TRUE(scene->step().ok);
  const auto& pipeline = dynamic_cast<const ContactPipeline&>(*scene->collisionPipeline());
  const int segments = 10;
  // Lying flat, every segment touches: two contacts each (its first and last sphere), where the
  // spheres alone would give ~134.
  EXPECT_LE(pipeline.contactCount(), 2 * segments);
  EXPECT_GE(pipeline.contactCount(), segments);
  // No point of the centre line, at a kept sphere or not, below one radius: the solve holds the
  // kept ones to its tolerance (1e-6 of the radius), and the gap is linear along a straight
  // segment, so the rest lie between them. And at rest on the table: one radius up.
  const CurveBody& rod = *scene->bodies().front()->curve();
  double lowest = 1.0, highest = 0.0;
  for (int k = 0; k <= 2000; ++k) {
    const double z = rod.position(scene->state().q, k / 2000.0).z();
    lowest = std::min(lowest, z);
    highest = std::max(highest, z);
  }
  EXPECT_GE(lowest, r * (1.0 - 1e-6));
  EXPECT_NEAR(highest, r, 1e-6 * r);
}

}  // namespace
}  // namespace filum::collision
