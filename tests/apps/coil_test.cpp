// apps/scenes/coil_in_sac.json as a trainer and a physicist would check it: the coil stays in the sac
// (every point of its centre line in the aneurysm, never deeper in the wall than a tenth of its
// radius), the wall carries its weight once it has settled (statics: the contact forces on the
// lumen add up to m g), and the packing density the run reports is π r² L / V with the coil's
// own length. The coil's length inside an aneurysm is checked on a straight rod across the dome.
#include <cmath>

#include <gtest/gtest.h>

#include "filum/all_components.hpp"
#include "filum/collision/contact_pipeline.hpp"
#include "filum/collision/vessel_lumen_obstacle.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/haptics/navigation_metrics.hpp"
#include "support/navigation_scene_run.hpp"

namespace filum {
namespace {

const std::string kCoilScene = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/coil_in_sac.json";

/// The polyline's length through `samples` + 1 points of the centre line (m).
double polylineLength(const CurveBody& body, const VecX& q, int samples) {
  double length = 0.0;
  for (int i = 0; i < samples; ++i)
    length += (body.position(q, static_cast<double>(i + 1) / samples) - body.position(q, static_cast<double>(i) / samples)).norm();
  return length;
}

TEST(CoilScene, StaysInTheSacWithItsWeightOnTheWall) {
  test::NavigationSceneRun run("coil_in_sac.json");
  const auto& scene = run.scene;
  const auto& metrics = run.metrics;
  ASSERT_NE(metrics, nullptr);
  ASSERT_NE(metrics->packing(), nullptr);
  const CurveBody& coil = *scene->bodies()[0]->curve();
  const geometry::VesselTree& tree = metrics->lumen().tree();
  const haptics::CoilPacking& aneurysm = *metrics->packing();
  const double r = coil.radius();
  const double dt = scene->settings().dt;
  // Settled: its velocities decay at the damping's 5/s and the contacts' Baumgarte rate; 0.4 s
  // is two damping times.
  const long steps = std::lround(0.4 / dt);
  double deepest = 0.0;
  int outside = 0;
  constexpr int kSamples = 480;  // every 0.125 mm, half a sphere spacing
  for (long k = 0; k < steps; ++k) {
    const StepReport report = run.step();
    ASSERT_TRUE(report.ok) << report.message;
    for (int i = 0; i <= kSamples; ++i) {
      const Vec3 x = coil.position(scene->state().q, static_cast<double>(i) / kSamples);
      if (!aneurysm.contains(x)) ++outside;
      deepest = std::max(deepest, test::wallDepth(tree.sample(x, tree.maxRadius()), r));
    }
  }
  std::printf("  deepest %.3f r, %d samples outside the aneurysm\n", deepest, outside);
  EXPECT_EQ(outside, 0);
  EXPECT_LT(deepest, 0.1);  // the bound: penetration below a tenth of the radius

  // Statics: Σ F on the lumen = m g (self-contacts act on the coil from both sides and cancel).
  const auto& pipeline = dynamic_cast<const collision::ContactPipeline&>(*scene->collisionPipeline());
  int lumen = -1;
  for (std::size_t o = 0; o < pipeline.obstacles().size(); ++o)
    if (pipeline.obstacles()[o] == &metrics->lumen()) lumen = static_cast<int>(o);
  ASSERT_GE(lumen, 0);
  const Vec3 weight = coil.mass() * scene->settings().gravity;
  const Vec3 on_wall = pipeline.obstacleForce(lumen, scene->state());
  // What is left of the motion: the drag −γ M v, and M dv/dt, against the weight.
  const double kinetic = scene->energy(scene->state()).kinetic;
  const double speed = std::sqrt(2.0 * kinetic / coil.mass());
  std::printf("  on the wall %.4e %.4e %.4e N, weight %.4e %.4e %.4e N; rms speed %.2e m/s\n", on_wall.x(), on_wall.y(),
              on_wall.z(), weight.x(), weight.y(), weight.z(), speed);
  // Tolerance: the drag of the motion left, γ m v_rms / (m g) = 5 v_rms / g (below 1e-6 for the
  // ~1e-7 m/s a settled coil keeps), and the contact solve's residual: it stops at
  // contact_tolerance = 1e-6 (LagrangeMultiplierSolver) of its largest term per row; summed over
  // the rows, at most (rows × 1e-6) of the largest force, itself below the weight. Measured ~1e-7.
  EXPECT_LT(5.0 * speed / weight.norm() * coil.mass(), 1e-6);
  const double rows = 3.0 * pipeline.contactCount();  // a normal and two friction rows each
  EXPECT_LT((on_wall - weight).norm(), (rows * 1e-6 + 1e-6) * weight.norm());

  // The packing density reported is π r² L / V with the whole coil in the sac.
  const double length = polylineLength(coil, scene->state().q, 4000);
  const double expected = M_PI * r * r * length / aneurysm.volume();
  // The metric's 512 chords against 4000 on the rod's polyline: a chord over a node cuts its
  // corner and loses at most l θ²/8 (coil_packing.hpp), θ = 0.5 mm × (1/3 mm⁻¹) = 1/6 rad the
  // turn at each of the 119 interior nodes, l = 60 mm / 512: 119 l θ²/8 / 60 mm = 8.1e-4.
  const double theta = 0.5 / 3.0, piece = length / 512;
  EXPECT_NEAR(metrics->packingDensity(), expected, 119 * piece * theta * theta / 8 / length * expected);
  const nlohmann::json summary = metrics->summary();
  EXPECT_DOUBLE_EQ(summary["aneurysm"]["packing_density"].get<double>(), metrics->packingDensity());
  EXPECT_EQ(summary["aneurysm"]["branches"], nlohmann::json({"neck", "sac"}));
}

nlohmann::json straightRodAcrossTheDome() {
  // A rod along x through the dome's centre (0, 0, 15 mm), 20 mm long; the dome's radius 4 mm.
  nlohmann::json document = readJsonFile(kCoilScene);
  auto& coil = document["nodes"][1]["components"][0];
  coil["nodes"] = {{"from", {-0.01, 0, 0.015}}, {"to", {0.01, 0, 0.015}}, {"count", 41}};
  return document;
}

TEST(CoilScene, LengthInsideTheAneurysmIsTheChordThroughTheDome) {
  const nlohmann::json document = straightRodAcrossTheDome();
  auto scene = loadScene(document, kCoilScene, app::makeFactory());
  auto metrics = haptics::NavigationMetrics::fromScene(document, kCoilScene, *scene);
  scene->init();
  const CurveBody& rod = *scene->bodies()[0]->curve();
  // The dome is a capsule of radius 4 mm whose axis (z from 14.8 to 15.2 mm) crosses z = 15 mm:
  // the chord along x there is 2 R = 8 mm. Error: at most one 20/512 mm piece at each crossing.
  const double inside = metrics->packing()->lengthInside(rod, scene->state().q);
  EXPECT_NEAR(inside, 8e-3, 2.0 * 0.02 / 512);
}

TEST(CoilScene, VolumeInsideTheAneurysmTakesEachSpansRadius) {
  // The straight rod across the dome with its second half thinner ("spans"): the volume inside is
  // π r₁² 4 mm + π r₂² 4 mm, the dome's chord split at the rod's middle (x = 0, s = 0.5).
  nlohmann::json document = straightRodAcrossTheDome();
  const double shaft = 0.127e-3, tip = 0.05e-3;
  auto& coil = document["nodes"][1]["components"];
  coil[0]["spans"] = {{{"from", 0.5}, {"to", 1.0}, {"radius", tip}}};
  coil[3].erase("spacing");  // the default, the thinnest section's radius: the tip's spheres touch
  auto scene = loadScene(document, kCoilScene, app::makeFactory());
  auto metrics = haptics::NavigationMetrics::fromScene(document, kCoilScene, *scene);
  scene->init();
  const CurveBody& rod = *scene->bodies()[0]->curve();
  ASSERT_TRUE(rod.radiusVaries());
  const haptics::CoilPacking::Inside inside = metrics->packing()->inside(rod, scene->state().q);
  // Errors: at most one 20/512 mm piece at each crossing of the dome's wall, each of the shaft's
  // section at most; the step at s = 0.5 falls on a piece's end (256 of 512), where no piece
  // straddles it.
  const double piece = 0.02 / 512;
  EXPECT_NEAR(inside.volume, M_PI * (shaft * shaft + tip * tip) * 4e-3, 2.0 * M_PI * shaft * shaft * piece);
  EXPECT_NEAR(inside.length, 8e-3, 2.0 * piece);
  // The density the run reports: this volume over the sac's (a few roundings of it).
  metrics->start(*scene);
  EXPECT_NEAR(metrics->packingDensity(), inside.volume / metrics->packing()->volume(),
              1e-12 * inside.volume / metrics->packing()->volume());
}

TEST(CoilScene, UnknownAneurysmBranchIsRefusedWithItsPlace) {
  nlohmann::json document = readJsonFile(kCoilScene);
  document["navigation"]["aneurysm"]["branches"] = {"neck", "dome"};
  auto scene = loadScene(document, kCoilScene, app::makeFactory());
  try {
    haptics::NavigationMetrics::fromScene(document, kCoilScene, *scene);
    FAIL() << "an unknown branch was accepted";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("aneurysm/branches"), std::string::npos) << message;
    EXPECT_NE(message.find("\"dome\""), std::string::npos) << message;
    EXPECT_NE(message.find("sac"), std::string::npos) << message;  // the known branches are listed
  }
}

TEST(CoilScene, BadAneurysmBlocksAreRefusedWithTheirPlace) {
  const auto refusal = [](const std::string& key, const nlohmann::json& value) {
    nlohmann::json document = readJsonFile(kCoilScene);
    document["navigation"]["aneurysm"][key] = value;
    auto scene = loadScene(document, kCoilScene, app::makeFactory());
    try {
      haptics::NavigationMetrics::fromScene(document, kCoilScene, *scene);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string twice = refusal("coils", {"coil", "coil"});
  EXPECT_NE(twice.find("aneurysm/coils"), std::string::npos) << twice;
  EXPECT_NE(twice.find("twice"), std::string::npos) << twice;
  const std::string open = refusal("branches", {"parent"});  // open at both ends: no volume
  EXPECT_NE(open.find("aneurysm/branches"), std::string::npos) << open;
  EXPECT_NE(open.find("open"), std::string::npos) << open;
  const std::string coarse = refusal("spacing", 1e-3);  // above a quarter of the neck's 2 mm radius
  EXPECT_NE(coarse.find("aneurysm/spacing"), std::string::npos) << coarse;
  const std::string fine = refusal("spacing", 1e-7);  // (16 mm / 0.1 µm)³ cells
  EXPECT_NE(fine.find("aneurysm/spacing"), std::string::npos) << fine;
  EXPECT_NE(fine.find("cells"), std::string::npos) << fine;
}

}  // namespace
}  // namespace filum
