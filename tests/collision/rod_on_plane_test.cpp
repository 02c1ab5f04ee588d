// A rod (FramedChain, segments of 2 cm) dropped onto a table through ~13 contact spheres per
// segment: the narrow phase keeps one contact per vertex against the flat table (keepSpanEnds,
// narrow_phase.cpp: its vertices are sphere centres) and the rod still rests on it with no sphere
// inside. Parallel faces at other heights keep their contacts.
#include <gtest/gtest.h>

#include <cstdio>

#include "filum/all_components.hpp"
#include "filum/collision/contact_pipeline.hpp"
#include "filum/collision/narrow_phase.hpp"
#include "filum/collision/obstacle.hpp"
#include "filum/constraints/lagrange_multiplier_solver.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"

namespace filum::collision {
namespace {

using nlohmann::json;

/// A polyurethane rod (E = 30 MPa, 1150 kg/m³; the FramedChain `chain` gives its nodes and
/// sections) 1.5 mm above a table, falling onto it: ImplicitEuler at 1 ms, unilateral contacts
/// with friction 0.3, the rod's spheres as `collision_model` sets them.
json rodAboveTable(const json& chain, const json& collision_model) {
  return {{"dt", 1e-3},
          {"gravity", {0, 0, -9.81}},
          {"integrator", {{"type", "ImplicitEuler"}}},
          {"constraint_solver", {{"type", "LagrangeMultiplierSolver"}}},
          {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"friction", 0.3}}},
          {"nodes",
           {{{"name", "rod"},
             {"components",
              {chain, {{"type", "ChainElasticity"}, {"youngs_modulus", 3e7}}, {{"type", "ViscousDamping"}, {"coefficient", 5.0}},
               collision_model}}},
            {{"name", "table"}, {"components", {{{"type", "PlaneObstacle"}, {"point", {0, 0, 0}}, {"normal", {0, 0, 1}}}}}}}}};
}

TEST(RodOnPlane, KeepsOneContactPerVertexAndNoSphereSinks) {
  const double r = 1e-3;
  const json document = rodAboveTable(
      {{"type", "FramedChain"}, {"nodes", {{"from", {0, 0, 1.5e-3}}, {"to", {0.2, 0, 1.5e-3}}, {"count", 11}}}, {"radius", r}, {"density", 1150}},
      {{"type", "SphereCollisionModel"}, {"spacing", 1.5e-3}});
  auto scene = loadScene(document, "rod on a plane", app::makeFactory());
  scene->init();
  for (int k = 0; k < 500; ++k) ASSERT_TRUE(scene->step().ok);
  const auto& pipeline = dynamic_cast<const ContactPipeline&>(*scene->collisionPipeline());
  const int segments = 10;
  // Lying flat, every vertex touches: one contact each (the gap is linear along a segment, so
  // its vertices' rows hold it), where the spheres alone would give ~134 and the two ends of
  // every segment's run of spheres 20.
  EXPECT_EQ(pipeline.contactCount(), segments + 1);
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

TEST(RodOnPlane, AThickShaftAndAThinTipEachRestOnTheirOwnRadius) {
  // A rod whose second half is a thin tip ("spans": radius 0.4 mm against the shaft's 1 mm) on a
  // table: each sphere takes its section's radius (at the node between the two, the larger), so
  // the shaft lies one shaft radius up and the tip, where it has come down, one tip radius —
  // where a single radius for the body held the tip 0.6 mm above the table. The tip comes down
  // from the shaft's height over the length a heavy elastic strip lifts off a step of δ = 0.6 mm,
  // (72 E I δ / w)^{1/4} ≈ 4.6 cm (E I = 6e-7 N m², w = ρ A g = 5.7e-3 N/m): from s = 0.8 on
  // (6 cm past the step) it lies flat. The tip's moment at the step is below the w ℓ² that would
  // lift the shaft's last node, so the shaft lies flat up to the step.
  const double shaft = 1e-3, tip = 4e-4;
  const json document = rodAboveTable({{"type", "FramedChain"},
                                       {"nodes", {{"from", {0, 0, 1.5e-3}}, {"to", {0.2, 0, 1.5e-3}}, {"count", 21}}},
                                       {"radius", shaft},
                                       {"density", 1150},
                                       {"spans", {{{"from", 0.5}, {"to", 1.0}, {"radius", tip}}}}},
                                      {{"type", "SphereCollisionModel"}});
  auto scene = loadScene(document, "rod with a thin tip on a plane", app::makeFactory());
  scene->init();
  for (int k = 0; k < 1000; ++k) ASSERT_TRUE(scene->step().ok) << "step " << k;
  const auto& pipeline = dynamic_cast<const ContactPipeline&>(*scene->collisionPipeline());
  const auto& model = *pipeline.models().front();
  EXPECT_EQ(model.radius(), shaft);
  EXPECT_EQ(model.smallestRadius(), tip);
  // Self-collision's default exclusion, 4 r of the thicker chord of a pair: the tip's own near
  // its end, the shaft's at its start and between the two.
  const int last = model.sphereCount() - 2;
  EXPECT_EQ(model.exclusion(last, last - 3), 4.0 * tip);
  EXPECT_EQ(model.exclusion(0, 3), 4.0 * shaft);
  EXPECT_EQ(model.exclusion(0, last), 4.0 * shaft);
  const CurveBody& rod = *scene->bodies().front()->curve();
  // The solve holds the kept contacts to its tolerance (1e-6 of the radius, as above), and a
  // straight segment's gap is linear between its vertices: no point of the centre line below its
  // own section's radius, and where the rod lies flat, exactly that high.
  for (int k = 0; k <= 2000; ++k) {
    const double s = k / 2000.0, z = rod.position(scene->state().q, s).z(), r = rod.radiusAt(s);
    EXPECT_GE(z, r * (1.0 - 1e-6)) << "s = " << s;
    if (s < 0.5) {
      EXPECT_NEAR(z, shaft, 1e-6 * shaft) << "s = " << s;
    }
    if (s >= 0.8) {
      EXPECT_NEAR(z, tip, 1e-6 * tip) << "s = " << s;
    }
  }
}

}  // namespace
}  // namespace filum::collision

namespace filum::collision {
namespace {

/// The rod of bench_rod's plane case: 50 nodes (4 mm segments), lying on a table with friction
/// 0.3, its s = 0 end dragged sideways at 5 cm/s; the contact Newton's steps solved as asked.
std::unique_ptr<Scene> draggedRod(const char* newton_linear_solve) {
  const double height = 1.2e-3;
  const json path = json::array({json{{"time", 0.0}, {"position", {0.0, 0.0, height}}},
                                 json{{"time", 10.0}, {"position", {0.0, 0.5, height}}}});
  const json document = {
      {"dt", 1e-3},
      {"gravity", {0, 0, -9.81}},
      {"integrator", {{"type", "ImplicitEuler"}}},
      {"constraint_solver", {{"type", "LagrangeMultiplierSolver"}, {"newton_linear_solve", newton_linear_solve}}},
      {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"friction", 0.3}}},
      {"nodes",
       {{{"name", "rod"},
         {"components",
          {{{"type", "FramedChain"}, {"nodes", {{"from", {0, 0, height}}, {"to", {0.2, 0, height}}, {"count", 50}}}, {"radius", 1e-3}, {"density", 1150}},
           {{"type", "ChainElasticity"}, {"youngs_modulus", 3e7}, {"poisson_ratio", 0.5}},
           {{"type", "ViscousDamping"}, {"coefficient", 2.0}},
           {{"type", "FixedPointConstraint"}, {"abscissa", 0.0}, {"path", path}},
           {{"type", "SphereCollisionModel"}, {"spacing", 1.5e-3}}}}},
        {{"name", "table"},
         {"components", {{{"type", "PlaneObstacle"}, {"point", {0, 0, 0}}, {"normal", {0, 0, 1}}, {"friction", 0.3}}}}}}}};
  auto scene = loadScene(document, "dragged rod", app::makeFactory());
  scene->init();
  return scene;
}

TEST(RodOnPlane, NewtonStepsThroughTheBandMoveTheRodAsDenseOnes) {
  // The structured step solves the same linear system as the dense LU (its Schur complement is
  // J_SS), so both runs take the same Newton iterates up to round-off and each solve stops at the
  // same tolerance, 1e-6 of its scale (contact_tolerance): the accelerations of one step differ
  // by at most ~1e-6 of g-sized terms, 1e-5 m/s², and 300 steps of 1 ms move a point by at most
  // ½ (0.3 s)² × 1e-5 m/s² ≈ 5e-7 m apart — if no contact takes another branch (stick/slip).
  // Checked at 1e-6 m (0.1 % of the rod's radius).
  auto dense = draggedRod("dense"), banded = draggedRod("auto");
  const auto* solver = dynamic_cast<const constraints::LagrangeMultiplierSolver*>(banded->constraintSolver());
  const auto* reference = dynamic_cast<const constraints::LagrangeMultiplierSolver*>(dense->constraintSolver());
  ASSERT_NE(solver, nullptr);
  ASSERT_NE(reference, nullptr);
  int structured = 0, dense_structured = 0;
  for (int k = 0; k < 300; ++k) {
    ASSERT_TRUE(dense->step().ok);
    ASSERT_TRUE(banded->step().ok);
    structured += solver->statistics().structured_steps;
    dense_structured += reference->statistics().structured_steps;
    // The same Newton iterates: the same count, the same outcome (of each step's last solve).
    EXPECT_EQ(solver->statistics().newton_iterations, reference->statistics().newton_iterations) << "step " << k;
    EXPECT_EQ(solver->statistics().fell_back, reference->statistics().fell_back) << "step " << k;
  }
  EXPECT_GT(structured, 300) << "the band was taken";
  EXPECT_EQ(dense_structured, 0);
  const VecX& a = dense->state().q;
  const VecX& b = banded->state().q;
  const int points = dense->bodies()[0]->pointCount();
  const double apart = (a.head(3 * points) - b.head(3 * points)).lpNorm<Eigen::Infinity>();
  std::printf("  dense and banded runs %.3g m apart after 300 steps, %d structured steps\n", apart, structured);
  EXPECT_LE(apart, 1e-6);
}

}  // namespace
}  // namespace filum::collision

namespace filum::collision {
namespace {

/// A table with a raised plate across it: the top z = 0 outside x ∈ [0.08, 0.12] m and z = h on
/// it, its normal +z on both: two parallel faces at different heights.
class SteppedTable final : public Obstacle {
 public:
  static constexpr double kPlate = 5e-4;  // h (m)
  std::string typeName() const override { return "SteppedTable"; }
  bool sample(const Vec3& x, double max_distance, SurfaceSample& out) const override {
    const double top = x.x() >= 0.08 && x.x() <= 0.12 ? kPlate : 0.0;
    out.point = Vec3(x.x(), x.y(), top);
    out.normal = Vec3::UnitZ();
    out.distance = x.z() - top;
    return out.distance < max_distance;
  }
};

TEST(RodOnPlane, AContactOnARaisedFaceIsKeptBetweenVerticesOnTheLowerOne) {
  // A straight 20 cm segment (two nodes) lying with its centre line one radius above z = 0, over
  // a plate 0.5 mm high in its middle: both vertices touch the table, the spheres over the plate
  // are 0.5 mm inside it. The plate's rows are not combinations of the vertices' (another plane,
  // although the same normal): they are kept, and against the plate.
  const double r = 1e-3;
  const json document = {
      {"dt", 1e-3},
      {"gravity", {0, 0, -9.81}},
      {"integrator", {{"type", "ImplicitEuler"}}},
      {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}}},
      {"nodes",
       {{{"name", "rod"},
         {"components",
          {{{"type", "FramedChain"}, {"nodes", {{"from", {0, 0, r}}, {"to", {0.2, 0, r}}, {"count", 2}}}, {"radius", r}, {"density", 1150}},
           {{"type", "ChainElasticity"}, {"youngs_modulus", 3e7}},
           {{"type", "SphereCollisionModel"}, {"spacing", 1.5e-3}}}}},
        {{"name", "far table"}, {"components", {{{"type", "PlaneObstacle"}, {"point", {0, 0, -1}}, {"normal", {0, 0, 1}}}}}}}}};
  auto scene = loadScene(document, "rod over a plate", app::makeFactory());
  scene->init();
  ASSERT_TRUE(scene->step().ok);  // (the spheres placed; the rod falls by g dt² = 10 µm)
  const auto& pipeline = dynamic_cast<const ContactPipeline&>(*scene->collisionPipeline());
  const SphereCollisionModel& model = *pipeline.models().front();
  NarrowPhaseSettings settings;
  settings.margin = 0.1 * r;
  ContactSet contacts;
  findObstacleContacts(model, 0, SteppedTable(), 0, settings, contacts);
  int on_plate = 0, vertices = 0;
  for (const Contact& c : contacts) {
    on_plate += c.surface_point.z() == SteppedTable::kPlate;
    const PointWeights& w = c.a.weights();
    vertices += w.count == 2 && (w.weight[0] == 0.0 || w.weight[1] == 0.0);
  }
  EXPECT_EQ(vertices, 2) << "both vertices touch the table";
  EXPECT_GE(on_plate, 1) << "a contact against the plate is kept: dropping it would let the rod sink 0.5 mm into it";
}

}  // namespace
}  // namespace filum::collision
