// Coaxial instruments (narrow_phase.hpp, findLumenContacts): a guidewire inside a tube held
// straight and level by clamps at both ends, gravity across them. The tube is a steel hypotube
// (E = 200 GPa) so that its floor is level: a polymer catheter clamped 20 cm apart sags under
// its weight with end slopes of ~1e-3, which tilts the floor's normals by as much and adds
// ±μ⁻¹·1e-3 ≈ 0.5 % to the axial force balance of a wire lying off the middle. References from the mechanics
// of a rigid body on a rough floor, computed here and not by the code under test:
// - at rest the wire lies on the bottom of the lumen, its centre line R_in − r below the
//   catheter's, and the lumen's contact forces carry exactly its weight m g;
// - pulled along the axis by F below μ m g it sticks (no creep); above, it slides with
//   m dv/dt = F − μ m g − c m v (Coulomb's kinetic friction with the viscous damping c of the
//   scene), stepped here by the same implicit Euler recurrence the scene uses;
// - the ordinary contacts between the two bodies, which would push the wire out through the wall,
//   are not sought.
#include <cmath>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "filum/all_components.hpp"
#include "filum/collision/contact_pipeline.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "support/tube_axis.hpp"

namespace filum::collision {
namespace {

using nlohmann::json;
using test::distanceToAxis;
using test::offsetFromAxis;

constexpr double kDt = 1e-3;            // s
constexpr double kGravity = 9.81;       // m/s²
constexpr double kTubeRadius = 1e-3;    // m, outer radius of the tube
constexpr double kLumenRadius = 6e-4;   // m
constexpr double kWireRadius = 4.45e-4; // m, a 0.035" wire
constexpr double kWireDensity = 4000;   // kg/m³
constexpr double kWireFrom = 0.02, kWireTo = 0.10;  // m along x, inside the catheter [0, 0.2]
constexpr double kFriction = 0.2;       // μ in the lumen
constexpr double kDamping = 1.0;        // c (1/s) of both bodies

double wireMass() { return M_PI * kWireRadius * kWireRadius * (kWireTo - kWireFrom) * kWireDensity; }

/// The scene: a catheter on the x axis clamped at both ends, a wire on its axis with an axial
/// load F (N) at its distal end from time 0.5 s (after it has settled on the bottom).
json coaxialScene(double pull) {
  json wire_components = {
      {{"type", "FramedChain"}, {"nodes", {{"from", {kWireFrom, 0, 0}}, {"to", {kWireTo, 0, 0}}, {"count", 17}}},
       {"radius", kWireRadius}, {"density", kWireDensity}},
      {{"type", "ChainElasticity"}, {"youngs_modulus", 2e9}, {"poisson_ratio", 0.3}},
      {{"type", "ViscousDamping"}, {"coefficient", kDamping}},
      {{"type", "SphereCollisionModel"}, {"inside", "catheter"}}};
  if (pull > 0.0)
    wire_components.push_back({{"type", "PointLoad"}, {"abscissa", 1.0},
                               {"path", {{{"time", 0.5}, {"force", {0, 0, 0}}}, {{"time", 0.5 + 1e-9}, {"force", {pull, 0, 0}}},
                                         {{"time", 10.0}, {"force", {pull, 0, 0}}}}}});
  return {{"dt", kDt},
          {"gravity", {0, 0, -kGravity}},
          {"integrator", {{"type", "ImplicitEuler"}}},
          {"constraint_solver", {{"type", "LagrangeMultiplierSolver"}}},
          {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}}},
          {"nodes",
           {{{"name", "catheter"},
             {"components",
              {{{"type", "FramedChain"}, {"nodes", {{"from", {0, 0, 0}}, {"to", {0.2, 0, 0}}, {"count", 21}}},
                {"radius", kTubeRadius}, {"density", 7900}},
               {{"type", "ChainElasticity"}, {"youngs_modulus", 2e11}, {"poisson_ratio", 0.3}},
               {{"type", "ViscousDamping"}, {"coefficient", kDamping}},
               {{"type", "ClampConstraint"}, {"abscissa", 0.0}},
               {{"type", "ClampConstraint"}, {"abscissa", 1.0}},
               {{"type", "SphereCollisionModel"}, {"lumen_radius", kLumenRadius}, {"lumen_friction", kFriction}}}}},
            {{"name", "wire"}, {"components", wire_components}}}}};
}

std::unique_ptr<Scene> load(const json& document) {
  auto scene = loadScene(document, "coaxial", app::makeFactory());
  scene->init();
  return scene;
}

const ContactPipeline& pipelineOf(const Scene& scene) {
  return dynamic_cast<const ContactPipeline&>(*scene.collisionPipeline());
}

/// The SceneError message of loading `document`, or "" when it loads.
std::string refusal(const json& document) {
  try {
    load(document);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

/// Mean x velocity of the wire's nodes (m/s): the velocity of its centre of mass to O(strain).
double meanAxialVelocity(const CurveBody& wire, const SceneState& s) {
  return wire.block(s.v).col(0).mean();
}

double meanAxialPosition(const CurveBody& wire, const SceneState& s) {
  return wire.block(s.q).col(0).mean();
}

TEST(Coaxial, WireRestsOnTheLumenFloorAndTheLumenCarriesItsWeight) {
  auto scene = load(coaxialScene(0.0));
  for (int k = 0; k < 500; ++k) ASSERT_TRUE(scene->step().ok) << "step " << k;
  const CurveBody& tube = *scene->bodies()[0]->curve();
  const CurveBody& wire = *scene->bodies()[1]->curve();
  const SceneState& s = scene->state();
  const auto& pipeline = pipelineOf(*scene);
  // Every point of the wire inside the lumen and the wire down on its floor: its centre line
  // R_in − r below the catheter's. The solve holds the kept contacts (sphere centres) to its
  // tolerance, and the segments between them lie no further out (convexity, narrow_phase.hpp);
  // a point sampled off the sphere centres at a node where the wire bends with the tube's sag
  // (κ ≈ 2e-3 1/m, θ = κ · 5 mm) lies out by up to h θ / 4 ≈ 1e-9 m, 7e-6 of the clearance:
  // 1e-4 of it asserted.
  const double clearance = kLumenRadius - kWireRadius;
  double farthest = 0.0;
  for (int k = 0; k <= 400; ++k) farthest = std::max(farthest, distanceToAxis(tube, s, wire.position(s.q, k / 400.0)));
  EXPECT_LE(farthest, clearance * (1.0 + 1e-4)) << farthest / clearance - 1.0;
  EXPECT_GE(farthest, clearance * (1.0 - 1e-4)) << "the wire did not come down to the lumen's floor";
  // On the floor, not against a side: every node's offset from the nearest point of the tube's
  // axis points straight down. The steel tube sags ~5 µm between its clamps, w L⁴/(384 E I),
  // with slopes below w L³/(72√3 E I) ≈ 1e-4 rad: the offset is within 1e-4 rad of −z, and its
  // cosine with −z above 1 − 1e-8 (1 − θ²/2 = 1 − 5e-9).
  const auto nodes = wire.block(s.q);
  for (int i = 0; i < wire.pointCount(); ++i)
    EXPECT_LT(offsetFromAxis(tube, s, nodes.row(i).transpose()).normalized().z(), -(1.0 - 1e-8)) << "node " << i;
  // The lumen's contacts, and no other, hold the wire: their vertical forces sum to m g up to
  // the wire's remaining motion (its momentum changes by M Δv̄ in a step, 1e-6 of m g here: it
  // has been at rest for 0.45 s) — 1e-4 m g asserted.
  int lumen = 0;
  Vec3 carried = Vec3::Zero();
  for (int i = 0; i < pipeline.contactCount(); ++i) {
    const Contact& c = pipeline.contacts()[i];
    ASSERT_TRUE(c.model_b == 0 && c.model_a == 1) << "contact " << i << " is not the wire inside the catheter";
    ++lumen;
    carried += pipeline.contactForce(i, s);
  }
  EXPECT_EQ(pipeline.statistics().lumen_contacts, lumen);
  EXPECT_EQ(pipeline.statistics().thread_contacts, 0) << "the pair's ordinary contacts are not sought";
  const double weight = wireMass() * kGravity;
  EXPECT_NEAR(carried.z(), weight, 1e-4 * weight);
  EXPECT_NEAR(carried.x(), 0.0, 1e-4 * weight);
  EXPECT_NEAR(carried.y(), 0.0, 1e-4 * weight);
  // Kept rows: the two ends of each run along one segment of the wire within one segment of the
  // tube. A run ends where the wire's segment changes (15 times) or the tube's chord crosses one
  // of the at most 9 tube nodes along the wire (in and out: 18 times): at most 2 (1 + 15 + 18)
  // rows, against one a sphere (~180) without the runs.
  EXPECT_LE(lumen, 2 * (1 + 15 + 18));
  EXPECT_LT(std::abs(meanAxialVelocity(wire, s)), 1e-9);
}

TEST(Coaxial, AWireWithAThinTipRestsAtEachSectionsClearanceFromTheAxis) {
  // The wire's distal half a thin tip ("spans": radius 0.3 mm against 0.445 mm), the whole wire
  // soft (E = 2e7 Pa, so that the tip comes down within the tube): each sphere's clearance is
  // R_in − r of its own section, so the shaft lies 0.155 mm and the tip 0.3 mm below the
  // catheter's axis — where one radius for the body held the tip at the shaft's 0.155 mm. The tip
  // comes down from the shaft's level over the lift-off length of a heavy strip clamped at a
  // step of δ = 0.145 mm, (72 E I δ / w)^{1/4}: 2.3 cm with the shaft's E I = 6.2e-7 N m² and
  // w = 0.0244 N/m, less with the tip's (E I / w ∝ r²): from s = 0.85 (2.8 cm past the step) it
  // lies on the floor. The tip's moment at the step is below the w ℓ² that would lift the
  // shaft's last node, so the shaft lies on its floor up to the step.
  constexpr double kTip = 3e-4;
  json document = coaxialScene(0.0);
  json& wire = document["nodes"][1]["components"];
  wire[0]["spans"] = json::array({{{"from", 0.5}, {"to", 1.0}, {"radius", kTip}}});
  wire[1]["youngs_modulus"] = 2e7;
  auto scene = load(document);
  for (int k = 0; k < 1000; ++k) ASSERT_TRUE(scene->step().ok) << "step " << k;
  const CurveBody& tube = *scene->bodies()[0]->curve();
  const CurveBody& curve = *scene->bodies()[1]->curve();
  const SceneState& s = scene->state();
  // As WireRestsOnTheLumenFloor…: the kept contacts held to the solve's tolerance, the points
  // between them no further out; 1e-4 of the clearance asserted.
  for (int k = 0; k <= 400; ++k) {
    const double u = k / 400.0, clearance = kLumenRadius - curve.radiusAt(u);
    const double d = distanceToAxis(tube, s, curve.position(s.q, u));
    EXPECT_LE(d, clearance * (1.0 + 1e-4)) << "s = " << u;
    if (u < 0.5) {
      EXPECT_NEAR(d, kLumenRadius - kWireRadius, 1e-4 * (kLumenRadius - kWireRadius)) << "s = " << u;
    }
    if (u >= 0.85) {
      EXPECT_NEAR(d, kLumenRadius - kTip, 1e-4 * (kLumenRadius - kTip)) << "s = " << u;
    }
  }
}

TEST(Coaxial, AWireRestsAtTheClearanceOfEachSectionOfANarrowingLumen) {
  // The catheter's lumen narrows from 0.6 mm to 0.5 mm from s = 0.3 on ("lumen_spans"; x = 6 cm),
  // under the middle of the wire (x from 2 to 10 cm); the wire soft (E = 2e7 Pa) as above. Each
  // sphere's clearance is the lumen's there less the wire's radius: the wire lies 0.155 mm below
  // the axis in the wide lumen and 0.055 mm in the narrow one — where one lumen radius held it at
  // 0.155 mm all along. The lumen's radius changes over the one chord of the tube's axis (1 mm)
  // that holds the step, whose narrow end is the corner the wire passes over. A heavy strip over
  // a corner δ above its floor, touching down on both floors (y = y' = y'' = 0 there, slope and
  // moment continuous at the corner): L₂ = (√3 − 1) L₁ past it and L₁ = (24 E I δ / ((2√3 − 3) w))^{1/4}
  // before it, 1.9 cm and 1.4 cm with δ = 0.1 mm, E I = 6.2e-7 N m², w = 0.0244 N/m. So it lies
  // on the wide floor for x <= 3.5 cm (touchdown at 4.1 cm or later) and on the narrow one from
  // 2 cm past the step (touchdown by 6.1 + 1.4 cm).
  constexpr double kNarrow = 5e-4, kStep = 0.06, kChord = 1e-3;
  json document = coaxialScene(0.0);
  document["nodes"][0]["components"][5]["lumen_spans"] = json::array({{{"from", 0.3}, {"to", 1.0}, {"lumen_radius", kNarrow}}});
  document["nodes"][1]["components"][1]["youngs_modulus"] = 2e7;
  auto scene = load(document);
  for (int k = 0; k < 1000; ++k) ASSERT_TRUE(scene->step().ok) << "step " << k;
  const CurveBody& tube = *scene->bodies()[0]->curve();
  const CurveBody& wire = *scene->bodies()[1]->curve();
  const SceneState& s = scene->state();
  const double wide = kLumenRadius - kWireRadius, narrow = kNarrow - kWireRadius;
  int on_wide = 0, on_narrow = 0;
  for (int k = 0; k <= 400; ++k) {
    const double u = k / 400.0;
    const Vec3 x = wire.position(s.q, u);
    const double d = distanceToAxis(tube, s, x);
    // As WireRestsOnTheLumenFloor…: the kept contacts held to the solve's tolerance, the points
    // between them no further out; 1e-4 of the clearance asserted.
    const double bound = x.x() < kStep + kChord ? wide : narrow;
    EXPECT_LE(d, bound * (1.0 + 1e-4)) << "s = " << u << ", x = " << x.x();
    if (x.x() <= 0.035) {
      EXPECT_NEAR(d, wide, 1e-4 * wide) << "s = " << u;
      ++on_wide;
    }
    if (x.x() >= kStep + 0.02) {
      EXPECT_NEAR(d, narrow, 1e-4 * narrow) << "s = " << u;
      ++on_narrow;
    }
  }
  EXPECT_GT(on_wide, 50);
  EXPECT_GT(on_narrow, 50);
}

TEST(Coaxial, LumenSpansTakeTheNarrowerSideAtTheirEndsAndTheLumenRadiusOnlyWhereNoSpanIs) {
  json document = coaxialScene(0.0);
  document["nodes"][0]["components"][5]["lumen_radius"] = 5e-4;
  // The tube's R_in(s) at the given abscissas, its narrowest and its widest, with these spans.
  auto expectLumen = [&](const json& spans, const std::vector<std::pair<double, double>>& at, double narrowest,
                         double widest) {
    document["nodes"][0]["components"][5]["lumen_spans"] = spans;
    auto scene = load(document);
    const SphereCollisionModel& tube = *pipelineOf(*scene).models()[0];
    for (const auto& [s, r] : at) EXPECT_EQ(tube.lumenRadiusAt(s), r) << "s = " << s << " with " << spans.dump();
    EXPECT_EQ(tube.narrowestLumen(), narrowest) << spans.dump();
    EXPECT_EQ(tube.lumenRadius(), widest) << spans.dump();
  };
  // Two spans meeting at s = 0.5 and covering the whole tube, both wider than "lumen_radius": the
  // lumen_radius holds nowhere, at the meeting point the narrower span's, at the tube's ends the
  // end span's.
  expectLumen(json::array({{{"from", 0.0}, {"to", 0.5}, {"lumen_radius", 6e-4}},
                           {{"from", 0.5}, {"to", 1.0}, {"lumen_radius", 5.5e-4}}}),
              {{0.0, 6e-4}, {0.25, 6e-4}, {0.5, 5.5e-4}, {1.0, 5.5e-4}}, 5.5e-4, 6e-4);
  // One span in the middle: the lumen_radius on both sides, the narrower at its ends.
  expectLumen(json::array({{{"from", 0.4}, {"to", 0.6}, {"lumen_radius", 5.5e-4}}}),
              {{0.0, 5e-4}, {0.4, 5e-4}, {0.5, 5.5e-4}, {1.0, 5e-4}}, 5e-4, 5.5e-4);
}

TEST(Coaxial, AnOpeningTakesTheLumenOfItsOwnEnd) {
  // A distal span narrows the lumen to 0.5 mm, the proximal end keeps 0.6 mm. A point 0.55 mm off
  // the axis beyond either end is in the proximal opening and outside the distal one.
  json document = coaxialScene(0.0);
  document["nodes"][0]["components"][5]["lumen_spans"] = json::array({{{"from", 0.9}, {"to", 1.0}, {"lumen_radius", 5e-4}}});
  auto scene = load(document);
  ASSERT_TRUE(scene->step().ok);  // the spheres' centres as of a step (the clamped tube barely sags)
  const SphereCollisionModel& tube = *pipelineOf(*scene).models()[0];
  const AxisPoint proximal = nearestAxisPoint(tube.centers(), tube.mapping(), Vec3(-1e-3, 0, 5.5e-4), nullptr, -1);
  const AxisPoint distal = nearestAxisPoint(tube.centers(), tube.mapping(), Vec3(0.201, 0, 5.5e-4), nullptr, -1);
  ASSERT_EQ(proximal.chord, -1);
  ASSERT_EQ(distal.chord, -1);
  EXPECT_EQ(proximal.end_sphere, 0);
  EXPECT_EQ(distal.end_sphere, tube.sphereCount() - 1);
  EXPECT_EQ(placeInTube(proximal, tube), TubePlace::kOpening);
  EXPECT_EQ(placeInTube(distal, tube), TubePlace::kOutside);
}

TEST(Coaxial, AHollowTubeHasItsWallsLumen) {
  // The catheter's section a tube's wall: a 0.6 mm lumen, narrowing to 0.5 mm over the segments
  // from s = 0.3 on (FramedChain "inner_radius", and a span's). Its SphereCollisionModel given no
  // lumen takes the wall's: the narrower side's at the step, as lumen spans do. A run with it is
  // bit for bit the run with the same lumen given as "lumen_radius" and "lumen_spans".
  json hollow = coaxialScene(0.0);
  json& chain = hollow["nodes"][0]["components"][0];
  chain["inner_radius"] = kLumenRadius;
  chain["spans"] = json::array({{{"from", 0.3}, {"to", 1.0}, {"inner_radius", 5e-4}}});
  hollow["nodes"][0]["components"][5].erase("lumen_radius");
  auto derived = load(hollow);
  const CurveBody& tube_body = *derived->bodies()[0]->curve();
  const std::vector<double> at = tube_body.sectionAbscissas();  // breakpoint, middle, breakpoint, ...
  const double step = at[12];                                     // node 6 of 21: s = 0.3
  const SphereCollisionModel& tube = *pipelineOf(*derived).models()[0];
  for (const auto& [s, r] : std::vector<std::pair<double, double>>{{0.0, kLumenRadius}, {0.15, kLumenRadius}, {step, 5e-4}, {0.5, 5e-4}, {1.0, 5e-4}})
    EXPECT_EQ(tube.lumenRadiusAt(s), r) << "s = " << s;
  EXPECT_EQ(tube.narrowestLumen(), 5e-4);
  EXPECT_EQ(tube.lumenRadius(), kLumenRadius);
  json given = hollow;
  given["nodes"][0]["components"][5]["lumen_radius"] = kLumenRadius;
  given["nodes"][0]["components"][5]["lumen_spans"] = json::array({{{"from", step}, {"to", 1.0}, {"lumen_radius", 5e-4}}});
  auto explicit_lumen = load(given);
  for (int k = 0; k < 300; ++k) {
    ASSERT_TRUE(derived->step().ok) << "step " << k;
    ASSERT_TRUE(explicit_lumen->step().ok) << "step " << k;
  }
  EXPECT_EQ(derived->state().q, explicit_lumen->state().q);
  // A lumen given wider than the wall's is refused, where it is given.
  const auto refusedAt = [](const json& document, const std::string& path) {
    const std::string what = refusal(document);
    EXPECT_NE(what.find(path), std::string::npos) << what;
  };
  json wide = hollow;
  wide["nodes"][0]["components"][5]["lumen_radius"] = 5.5e-4;  // wider than the distal wall's 0.5 mm
  refusedAt(wide, "components/5/lumen_radius: expected a lumen within the tube's wall");
  wide["nodes"][0]["components"][5]["lumen_radius"] = 5e-4;
  wide["nodes"][0]["components"][5]["lumen_spans"] = json::array({{{"from", 0.0}, {"to", 0.2}, {"lumen_radius", 6.5e-4}}});
  refusedAt(wide, "components/5/lumen_spans/0/lumen_radius: expected a lumen within the tube's wall");
  wide["nodes"][0]["components"][5]["lumen_radius"] = 6.5e-4;  // the base too wide, the span not
  wide["nodes"][0]["components"][5]["lumen_spans"] = json::array({{{"from", step}, {"to", 1.0}, {"lumen_radius", 5e-4}}});
  refusedAt(wide, "components/5/lumen_radius: expected a lumen within the tube's wall");
}

TEST(Coaxial, RefusesLumenSpansThatDoNotFit) {
  const auto refusedAt = [](const json& document, const std::string& path) {
    const std::string what = refusal(document);
    EXPECT_NE(what.find(path), std::string::npos) << what;
  };
  json document = coaxialScene(0.0);
  json& tube = document["nodes"][0]["components"][5];
  tube["lumen_spans"] = json::array({{{"from", 0.3}, {"to", 1.0}, {"lumen_radius", 1.2e-3}}});
  refusedAt(document, "lumen_spans/0/lumen_radius");  // wider than the tube
  tube["lumen_spans"] = json::array({{{"from", 0.3}, {"to", 0.8}, {"lumen_radius", 5e-4}},
                                     {{"from", 0.7}, {"to", 1.0}, {"lumen_radius", 5.5e-4}}});
  refusedAt(document, "lumen_spans/1/from");  // overlapping spans
  tube["lumen_spans"] = json::array({{{"from", 0.8}, {"to", 0.3}, {"lumen_radius", 5e-4}}});
  refusedAt(document, "lumen_spans/0/to");
  tube["lumen_spans"] = json::array({{{"from", 0.3}, {"to", 1.0}, {"lumen_radius", 0.9 * kWireRadius}}});
  refusedAt(document, "inside");  // the wire does not fit the narrowest section
  tube.erase("lumen_radius");
  tube.erase("lumen_friction");
  tube["lumen_spans"] = json::array({{{"from", 0.3}, {"to", 1.0}, {"lumen_radius", 5e-4}}});
  refusedAt(document, "components/5/lumen_spans (SphereCollisionModel): expected a \"lumen_radius\" beside it");  // no lumen outside
}

/// The wire's mean axial displacement 0.5 s after the pull began (m), and its axial speed then.
struct Slide {
  double displacement = 0.0, speed = 0.0;
};

Slide pullFor(double pull, double seconds) {
  auto scene = load(coaxialScene(pull));
  const CurveBody& wire = *scene->bodies()[1]->curve();
  for (int k = 0; k < 500; ++k) EXPECT_TRUE(scene->step().ok) << "step " << k;
  const double start = meanAxialPosition(wire, scene->state());
  const int steps = static_cast<int>(std::lround(seconds / kDt));
  for (int k = 0; k < steps; ++k) EXPECT_TRUE(scene->step().ok) << "step " << 500 + k;
  return {meanAxialPosition(wire, scene->state()) - start, meanAxialVelocity(wire, scene->state())};
}

TEST(Coaxial, WireSticksBelowTheCoulombLimitWithoutCreep) {
  const double limit = kFriction * wireMass() * kGravity;  // μ m g: the floor's normal force is m g
  const Slide held = pullFor(0.8 * limit, 0.5);
  // Held: no creep, less than 0.01 mm/s (issue 27's bound for a held contact); in displacement,
  // 1e-6 m, fifty times the wire's elastic stretch under the load (F L / (E A) ≈ 2e-8 m) and
  // five times below what the creep bound would allow over the 0.5 s (5e-6 m).
  EXPECT_LT(std::abs(held.speed), 1e-5);
  EXPECT_LT(std::abs(held.displacement), 1e-6);
}

TEST(Coaxial, WireSlidesAboveTheCoulombLimitAsARigidBodyOnARoughFloor) {
  const double mass = wireMass(), limit = kFriction * mass * kGravity;
  const double pull = 1.25 * limit, seconds = 0.3;
  const Slide slid = pullFor(pull, seconds);
  // m (v_n − v_{n−1}) / h = F − μ m g − c m v_n, x_n = x_{n−1} + h v_n (implicit Euler, as the
  // scene steps), from rest.
  const double a0 = (pull - limit) / mass;
  double v = 0.0, x = 0.0;
  const int steps = static_cast<int>(std::lround(seconds / kDt));
  for (int n = 0; n < steps; ++n) {
    v = (v + kDt * a0) / (1.0 + kDt * kDamping);
    x += kDt * v;
  }
  // 2 %: the rigid-body model leaves out the wire's axial wave (its stretch F L/(E A), 3e-8 m)
  // and the first step of the pull, where the contact passes from stick to slip within one step
  // (h a0 h ≈ 5e-7 m of 20 mm); the bound for a slip against the Coulomb prediction.
  EXPECT_NEAR(slid.displacement, x, 0.02 * x);
  EXPECT_NEAR(slid.speed, v, 0.02 * v);
}

TEST(Coaxial, AStepThatTakesTheWireOutThroughTheWallIsHalved) {
  // missedContact (contact_pipeline.hpp): from the step's start (the wire on the floor), a state
  // with the wire's middle node moved down through the wall by 2 r is a step to redo in halves
  // (it ends beyond the allowed p (R_in − r), p = ½, past the wall and further out than it began); the
  // state the step really reached is not; nor is a step that ends with the wire still deeper
  // inside the lumen.
  auto scene = load(coaxialScene(0.0));
  for (int k = 0; k < 300; ++k) ASSERT_TRUE(scene->step().ok);
  auto& pipeline = const_cast<ContactPipeline&>(pipelineOf(*scene));
  pipeline.beginStep(*scene, scene->state(), kDt);
  EXPECT_EQ(pipeline.missedContact(scene->state()), CollisionPipeline::Miss::kNone);
  SceneState out = scene->state();
  const CurveBody& wire = *scene->bodies()[1]->curve();
  wire.block(out.q)(8, 2) -= 2.0 * kWireRadius;
  EXPECT_EQ(pipeline.missedContact(out), CollisionPipeline::Miss::kOverlapOrSlide);
  SceneState in = scene->state();
  wire.block(in.q)(8, 2) += 0.5 * (kLumenRadius - kWireRadius);
  EXPECT_EQ(pipeline.missedContact(in), CollisionPipeline::Miss::kNone);
}

TEST(Coaxial, ASphereCrossingTheLumenIsHeldByTheWallItIsHeadingFor) {
  // At rest on the floor, every lumen contact's normal points up (from the floor to the axis).
  // The same wire thrown upwards at 2 (R_in − r) / h, which would carry it across the lumen
  // within the step, gets the rows of the roof instead (normals down), where it is going: the
  // floor's rows could only stop it moving down.
  auto scene = load(coaxialScene(0.0));
  for (int k = 0; k < 300; ++k) ASSERT_TRUE(scene->step().ok);
  auto& pipeline = const_cast<ContactPipeline&>(pipelineOf(*scene));
  pipeline.beginStep(*scene, scene->state(), kDt);
  ASSERT_GT(pipeline.contactCount(), 0);
  for (const Contact& c : pipeline.contacts()) EXPECT_GT(c.normal.z(), 0.99);
  SceneState thrown = scene->state();
  const CurveBody& wire = *scene->bodies()[1]->curve();
  wire.block(thrown.v).col(2).setConstant(2.0 * (kLumenRadius - kWireRadius) / kDt);
  pipeline.beginStep(*scene, thrown, kDt);
  ASSERT_GT(pipeline.contactCount(), 0);
  for (const Contact& c : pipeline.contacts()) EXPECT_LT(c.normal.z(), -0.99);
}

TEST(Coaxial, AWirePushedInThroughTheHubAndOutOfTheTipTouchesNoEndOfTheTube) {
  // apps/scenes/wire_in_catheter.json to 1.5 s: the wire enters the catheter at its hub (its part
  // behind the hub is in line with the lumen: the opening), slides along the floor and leaves
  // the tip from 0.75 s on. It never touches the tube's ends or outer surface (no thread–thread
  // contact between the two), its part inside stays in the lumen, and its part out of the tip is
  // free and bends down under its weight.
  const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/wire_in_catheter.json";
  auto scene = loadScene(readJsonFile(path), path, app::makeFactory());
  scene->init();
  const auto& pipeline = pipelineOf(*scene);
  const CurveBody& tube = *scene->bodies()[0]->curve();
  const CurveBody& wire = *scene->bodies()[1]->curve();
  const double clearance = 5.3e-4 - 4.45e-4;
  while (scene->state().time < 1.5 - 1e-9) {
    ASSERT_TRUE(scene->step().ok) << "t = " << scene->state().time;
    ASSERT_EQ(pipeline.statistics().thread_contacts, 0) << "t = " << scene->state().time;
  }
  const SceneState& s = scene->state();
  const double tube_end = tube.position(s.q, 1.0).x();
  EXPECT_GT(wire.position(s.q, 1.0).x(), tube_end + 0.01) << "the wire is out of the tip by more than 1 cm";
  for (int k = 0; k <= 500; ++k) {
    const Vec3 x = wire.position(s.q, k / 500.0);
    // Inside the tube's length (away from its ends by a segment): in the lumen, within p = ½ of
    // the clearance beyond the wall, the bound missedContact redoes steps for.
    if (x.x() > 0.005 && x.x() < tube_end - 0.005) {
      EXPECT_LE(distanceToAxis(tube, s, x), 1.5 * clearance) << "s = " << k / 500.0;
    }
  }
  EXPECT_LT(wire.position(s.q, 1.0).y(), -1e-4) << "the free end bends down under its weight";
  // Nor is a step redone for the ends: the parts of the wire in line with the openings are not
  // compared with the tube's end chords (a wire entering a hub would otherwise halve every step).
  EXPECT_EQ(scene->contactHalvings(), 0);
}

/// A stiff 0.035" wire pushed at 3 cm/s into a 5 F catheter whose last 3 cm turn by 45° (κ =
/// 26.2 rad/m, built in its curved shape), with the friction rows' rate ω_f ("friction_rate").
json wireIntoACurve(double friction_rate) {
  json catheter_nodes = json::array();
  for (int k = 0; k <= 18; ++k) catheter_nodes.push_back({0.005 * k, 0.0, 0.0});  // straight 9 cm
  const double bend = 1.0 / 26.2;                                                  // m
  for (int k = 1; k <= 6; ++k) {
    const double a = 0.005 * k / bend;
    catheter_nodes.push_back({0.09 + bend * std::sin(a), bend * (1.0 - std::cos(a)), 0.0});
  }
  return {{"dt", kDt},
          {"gravity", {0, -kGravity, 0}},
          {"integrator", {{"type", "ImplicitEuler"}}},
          {"constraint_solver", {{"type", "LagrangeMultiplierSolver"}}},
          {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"friction", 0.1}, {"friction_rate", friction_rate}}},
          {"nodes",
           {{{"name", "catheter"},
             {"components",
              {{{"type", "FramedChain"}, {"nodes", catheter_nodes}, {"radius", 8.3e-4}, {"density", 1150}},
               {{"type", "ChainElasticity"}, {"youngs_modulus", 1e9}, {"poisson_ratio", 0.4}, {"rest_shape", "initial"}},
               {{"type", "RodEndFrame"}, {"end", "start"}},
               {{"type", "FixedPointConstraint"}, {"abscissa", 0.0}},
               {{"type", "ViscousDamping"}, {"coefficient", 5.0}},
               {{"type", "SphereCollisionModel"}, {"self_collision", false}, {"lumen_radius", 5.3e-4}, {"lumen_friction", 0.05}}}}},
            {{"name", "wire"},
             {"components",
              {{{"type", "FramedChain"}, {"nodes", {{"from", {-0.04, 0, 0}}, {"to", {0.06, 0, 0}}, {"count", 41}}},
                {"radius", kWireRadius}, {"density", kWireDensity}},
               {{"type", "ChainElasticity"}, {"youngs_modulus", 2e9}, {"poisson_ratio", 0.3}},
               {{"type", "RodEndFrame"}, {"end", "start"}},
               {{"type", "FixedPointConstraint"}, {"abscissa", 0.0},
                {"path", {{{"time", 0.0}, {"position", {-0.04, 0, 0}}}, {{"time", 0.5}, {"position", {-0.04, 0, 0}}},
                          {{"time", 2.5}, {"position", {0.02, 0, 0}}}}}},
               {{"type", "ViscousDamping"}, {"coefficient", 5.0}},
               {{"type", "SphereCollisionModel"}, {"self_collision", false}, {"inside", "catheter"}}}}}}}};
}

TEST(Coaxial, AStiffWireGoesRoundATightCurveWithSlowFrictionRows) {
  // The case docs/vessels.md records: with the friction rows' default rate ω_f = 0.5/dt the wire's
  // tip's motion across the lumen grows once it enters the curve and the run diverges at
  // t ≈ 1.78 s (at 200/s, at 2.0 s: wireIntoACurve(200)). At ω_f = 100/s (ω_f dt = 0.1) the tip
  // goes round: pushed 6 cm, it reaches the catheter's tip at 2.5 s. Every point of the wire
  // inside the catheter, away from its tip by 5 mm (the nearest-point distance clamps at the
  // last node), is checked at every step against (1 + p) of the clearance, p = ½: the level at
  // which missedContact redoes a step in halves — not an invariant (at the finest sub-step a
  // deeper point is kept), so the measured figure is printed with the halvings.
  auto scene = load(wireIntoACurve(100.0));
  const CurveBody& tube = *scene->bodies()[0]->curve();
  const CurveBody& wire = *scene->bodies()[1]->curve();
  const double clearance = 5.3e-4 - kWireRadius;
  double worst = 0.0, worst_time = 0.0;
  while (scene->state().time < 2.6 - 1e-9) {
    const StepReport report = scene->step();
    ASSERT_TRUE(report.ok) << report.message;
    const SceneState& s = scene->state();
    const Vec3 tube_tip = tube.position(s.q, 1.0);
    for (int k = 0; k <= 200; ++k) {
      const Vec3 x = wire.position(s.q, k / 200.0);
      if (x.x() <= 0.005 || (x - tube_tip).norm() < 0.005) continue;  // behind the hub, at the tip
      const double d = distanceToAxis(tube, s, x) / clearance;
      if (d > worst) worst = d, worst_time = s.time;
    }
  }
  const SceneState& s = scene->state();
  std::printf("  tip %.2f mm from the catheter's tip; farthest from the axis %.2f clearances (t = %.3f s); %ld "
              "contact halvings\n",
              1e3 * (wire.position(s.q, 1.0) - tube.position(s.q, 1.0)).norm(), worst, worst_time,
              scene->contactHalvings());
  // The hub pushed 6 cm along the catheter's 12 cm: the tip ends at the catheter's tip (to the
  // clearance and the inner or outer track round the curve, ~0.2 mm); 3 mm tells "went round"
  // from the failure, stuck or diverged at the curve's entry 30 mm short.
  EXPECT_LT((wire.position(s.q, 1.0) - tube.position(s.q, 1.0)).norm(), 3e-3);
  EXPECT_LE(worst, 1.5);
}

TEST(Coaxial, RefusesTubesThatCannotHoldTheWire) {
  const auto contains = [](const std::string& what, const std::string& text) {
    return what.find(text) != std::string::npos;
  };
  json document = coaxialScene(0.0);
  document["nodes"][0]["components"][5].erase("lumen_radius");
  document["nodes"][0]["components"][5].erase("lumen_friction");
  std::string what = refusal(document);  // a wire inside a catheter without a lumen
  EXPECT_TRUE(contains(what, "inside") && contains(what, "without a lumen_radius")) << what;
  document = coaxialScene(0.0);
  document["nodes"][1]["components"][3]["inside"] = "sheath";
  what = refusal(document);  // a wire inside a node that does not exist: the known ones listed
  EXPECT_TRUE(contains(what, "\"catheter\"") && contains(what, "\"sheath\"")) << what;
  document = coaxialScene(0.0);
  document["nodes"][0]["components"][5]["lumen_radius"] = 2e-3;
  EXPECT_FALSE(refusal(document).empty()) << "a lumen wider than the tube";
  document = coaxialScene(0.0);
  document["nodes"][0]["components"][5]["lumen_radius"] = 0.9 * kWireRadius;
  what = refusal(document);  // a lumen narrower than the wire
  EXPECT_TRUE(contains(what, "above this instrument's radius")) << what;
  // One level of coaxial instruments: the catheter inside a sheath while it holds the wire.
  document = coaxialScene(0.0);
  document["nodes"][0]["components"][5]["inside"] = "sheath";
  document["nodes"].push_back({{"name", "sheath"},
                               {"components",
                                {{{"type", "FramedChain"}, {"nodes", {{"from", {0, 0, 0}}, {"to", {0.2, 0, 0}}, {"count", 5}}},
                                  {"radius", 2e-3}, {"density", 1150}},
                                 {{"type", "SphereCollisionModel"}, {"lumen_radius", 1.5e-3}}}}});
  what = refusal(document);
  EXPECT_TRUE(contains(what, "one level")) << what;
}

TEST(Coaxial, AWireBesideTheTubeIsNotPulledInButRestsOnItsOuterSurface) {
  // The wire declared inside the tube but lying beside it, 1 mm above its outer surface (a wire
  // out of the tip and curled back): not held by the lumen, it falls onto the tube and rests on
  // top of it, its centre line R_out + r above the tube's (two threads touching).
  json document = coaxialScene(0.0);
  const double z = kTubeRadius + kWireRadius + 1e-3;
  document["nodes"][1]["components"][0]["nodes"] = {{"from", {kWireFrom, 0, z}}, {"to", {kWireTo, 0, z}}, {"count", 17}};
  auto scene = load(document);
  for (int k = 0; k < 500; ++k) ASSERT_TRUE(scene->step().ok) << "step " << k;
  const auto& pipeline = pipelineOf(*scene);
  EXPECT_EQ(pipeline.statistics().lumen_contacts, 0);
  EXPECT_GT(pipeline.statistics().thread_contacts, 0);
  const CurveBody& wire = *scene->bodies()[1]->curve();
  // Resting contacts hold the centre lines R_out + r apart to the solve's tolerance; 1e-4 m (7 %
  // of R_out + r) only tells resting on the outer surface from being inside (z < 0) or still
  // falling. (Resting on top of a frictionless cylinder is an unstable balance, kept here by the
  // exact symmetry about y = 0.)
  const auto nodes = wire.block(scene->state().q);
  for (int i = 0; i < wire.pointCount(); ++i) EXPECT_NEAR(nodes(i, 2), kTubeRadius + kWireRadius, 1e-4) << "node " << i;
}

}  // namespace
}  // namespace filum::collision
