// apps/scenes/guidewire.json as a trainer would check it: the scripted push-and-turn takes the
// guidewire's tip into the left common carotid, and the same push without the turn does not (the
// wire rides straight up into the left subclavian: the turn is what steers it); the wire never
// leaves the lumen (penetration below a tenth of its radius at every step); the navigation
// metrics report what happened (the tip's branch, the target, the hub's push and roll, the wall force).
// apps/scenes/catheter_device.json: the same done by a hand on a haptic device, in strokes.
// apps/scenes/catheter.json: then a catheter advanced over the wire into the carotid.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "filum/all_components.hpp"
#include "filum/collision/vessel_lumen_obstacle.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/haptics/navigation_metrics.hpp"
#include "filum/run_command.hpp"
#include "support/navigation_scene_run.hpp"
#include "support/tube_axis.hpp"

namespace filum {
namespace {

struct NavigationRun {
  std::string tip_branch;
  double reached_time = -1.0;
  double worst_penetration = 0.0;  // of the wire's radius
  double worst_time = 0.0, worst_abscissa = 0.0;  // where and when
  double inserted = 0.0, roll = 0.0, target_distance = 0.0, max_wall_force = 0.0, time_above_limit = 0.0;
  bool ok = true;
};

// The centre line sampled every 0.5 mm: one or two samples between neighbouring sphere centres
// (0.76 mm apart), where the union of the spheres is thinnest.
constexpr int kSamples = 400;
NavigationRun navigate(bool turn) {
  test::NavigationSceneRun navigation("guidewire.json", [turn](nlohmann::json& document) {
    if (turn) return;  // the negative control: the hub pushed the same way, never turned
    for (auto& component : document["nodes"][1]["components"])
      if (component["type"] == "RodEndFrame") component["path"] = {{{"time", 0.0}, {"roll", 0.0}}};
  });
  const auto& scene = navigation.scene;
  const auto& metrics = navigation.metrics;
  const CurveBody& wire = *scene->bodies()[0]->curve();
  const geometry::VesselTree& tree = metrics->lumen().tree();
  NavigationRun run;
  const long steps = navigation.steps();
  for (long k = 0; k < steps && run.ok; ++k) {
    const StepReport report = navigation.step();
    run.ok = report.ok;
    EXPECT_TRUE(report.ok) << report.message;
    for (int i = 0; i <= kSamples; ++i) {
      const Vec3 x = wire.position(scene->state().q, static_cast<double>(i) / kSamples);
      const geometry::VesselTree::Sample s = tree.sample(x, tree.maxRadius());
      if (s.branch < 0) continue;
      const double depth = test::wallDepth(s, wire.radius());
      if (depth > run.worst_penetration) {
        run.worst_penetration = depth;
        run.worst_time = scene->state().time;
        run.worst_abscissa = static_cast<double>(i) / kSamples;
      }
    }
  }
  const auto& m = metrics->instrument(0);
  run.tip_branch = m.branch >= 0 ? tree.branch(m.branch).name : "outside";
  run.reached_time = m.reached_time;
  run.inserted = m.inserted;
  run.roll = m.roll;
  run.target_distance = m.target_distance;
  run.max_wall_force = m.max_wall_force;
  run.time_above_limit = m.time_above_limit;
  return run;
}

TEST(CatheterScene, TurningTheHubSteersTheWireIntoTheCarotid) {
  const NavigationRun run = navigate(true);
  std::printf("  tip in %s (reached at %.2f s), %.1f mm from the target; inserted %.1f mm, roll %.0f°; deepest %.3f r; "
              "wall force max %.3f N\n",
              run.tip_branch.c_str(), run.reached_time, 1e3 * run.target_distance, 1e3 * run.inserted,
              run.roll * 180 / M_PI, run.worst_penetration, run.max_wall_force);
  ASSERT_TRUE(run.ok);
  EXPECT_EQ(run.tip_branch, "left_common_carotid");
  EXPECT_GT(run.reached_time, 0.0);
  // The target point lies at z = 13 cm, 4.5 cm up the carotid, 2.6 mm off its axis; the tip ends
  // within the vessel's radius (4 mm) of it.
  EXPECT_LT(run.target_distance, 4e-3);
  EXPECT_LT(run.worst_penetration, 0.1);
  // The hub was pushed 19.5 cm along the introducer's axis (the path's two ends) and turned by 3.61 rad.
  // The hub's rows hold its position and velocity to the path's (Ẋ in the Baumgarte term), so a
  // path at constant speed is followed without lag, to the solver's tolerance (measured 0.00 mm);
  // asked within 0.2 mm, under a tenth of a segment (3 mm).
  EXPECT_NEAR(run.inserted, 0.195, 2e-4);
  EXPECT_DOUBLE_EQ(run.roll, 3.61);
  // The wall force was measured (the wire lies on the wall) and stayed below the scene's limit of
  // 0.5 N, where a trainer would flag a push that risks a dissection: this run is gentle.
  EXPECT_GT(run.max_wall_force, 0.0);
  EXPECT_LT(run.max_wall_force, 0.5);
  EXPECT_EQ(run.time_above_limit, 0.0);
}

TEST(CatheterScene, WithoutTheTurnTheWireGoesIntoTheSubclavian) {
  const NavigationRun run = navigate(false);
  std::printf("  tip in %s; deepest %.3f r at t = %.3f s, s = %.2f\n", run.tip_branch.c_str(), run.worst_penetration,
              run.worst_time, run.worst_abscissa);
  ASSERT_TRUE(run.ok);
  EXPECT_EQ(run.tip_branch, "left_subclavian");
  EXPECT_LT(run.reached_time, 0.0);
  EXPECT_LT(run.worst_penetration, 0.1);
}

TEST(CatheterScene, AHandOnAHapticDeviceFeedsTheWireIntoTheCarotidInStrokes) {
  namespace fs = std::filesystem;
  const fs::path out = fs::path(FILUM_BINARY_DIR) / "test_output" / "catheter_device";
  fs::remove_all(out);
  app::RunOptions options;
  options.scene = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/catheter_device.json";
  options.out = out.string();
  options.progress = false;
  std::ostringstream log, progress;
  ASSERT_EQ(app::runScene(options, log, progress), app::kRunOk) << log.str();
  EXPECT_NE(log.str().find("5 strokes"), std::string::npos) << log.str();
  const nlohmann::json metrics = readJsonFile((out / "metrics.json").string());
  const nlohmann::json& wire = metrics["instruments"]["guidewire"];
  EXPECT_EQ(wire["tip_branch"], "left_common_carotid");
  EXPECT_EQ(wire["reached_target_branch"], true);
  // Five strokes of 3.9 cm: the hub's target is set from the stylus by arithmetic (round-off); the
  // hub follows it within the constraint's error, which Baumgarte's critically damped term
  // (ω = 0.1/dt = 100/s) shrinks by (1 + ω t) e^(−ω t) ≈ 4e-8 over the 0.2 s held at the end: a
  // lag of even a segment (3 mm) is then 1e-10 m; asked within 1 µm.
  EXPECT_NEAR(wire["inserted_length"].get<double>(), 0.195, 1e-6);
  EXPECT_NEAR(wire["roll"].get<double>(), 3.61, 1e-12);  // the stylus turned 3.61 rad in the second stroke
  // haptics.csv: one row per servo tick; the force along the introducer only (scene z, device −z:
  // the device's x and y get nothing), nothing while the grip is released; the torque asked for
  // but not sent (a Touch has no motor on its gimbal).
  std::ifstream csv(out / "haptics.csv");
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_NE(line.find("roll,torque_commanded,torque_sent"), std::string::npos) << line;
  int rows = 0, released = 0;
  double largest_torque = 0.0, previous_buttons = 1.0;
  while (std::getline(csv, line)) {
    std::istringstream fields(line);
    std::vector<double> v;
    for (std::string cell; std::getline(fields, cell, ',');) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 16u) << line;
    ++rows;
    EXPECT_EQ(v[9], 0.0);   // sent x
    EXPECT_EQ(v[10], 0.0);  // sent y
    // Released since the tick before: the model of a step taken without the grip, nothing felt
    // (at the first released tick the model is still the last gripped step's).
    if (v[5] == 0.0 && previous_buttons == 0.0) {
      ++released;
      EXPECT_EQ(v[8], 0.0) << line;  // commanded z
    }
    previous_buttons = v[5];
    largest_torque = std::max(largest_torque, std::abs(v[14]));
    EXPECT_EQ(v[15], 0.0);  // torque sent
  }
  EXPECT_EQ(rows, 6000);
  EXPECT_GT(released, 0);
  EXPECT_GT(largest_torque, 0.0);
}

TEST(CatheterScene, TheCatheterFollowsTheWireIntoTheCarotid) {
  // apps/scenes/catheter.json: the wire steered into the left common carotid with the
  // catheter behind it (0-6 s), then the catheter pushed 15 cm over the held wire (6-10 s).
  test::NavigationSceneRun run("catheter.json");
  const nlohmann::json& document = run.document;
  const auto& scene = run.scene;
  const auto& metrics = run.metrics;
  ASSERT_NE(metrics, nullptr);
  // The scene's nodes: vessels, catheter, guidewire (bodies in that order); the navigation block
  // lists the guidewire first.
  ASSERT_EQ(document["nodes"][1]["name"], "catheter");
  ASSERT_EQ(document["nodes"][2]["name"], "guidewire");
  ASSERT_EQ(metrics->instrumentCount(), 2);
  ASSERT_EQ(metrics->instrument(0).name, "guidewire");
  ASSERT_EQ(metrics->instrument(1).name, "catheter");
  const CurveBody& catheter = *scene->bodies()[0]->curve();
  const CurveBody& wire = *scene->bodies()[1]->curve();
  const geometry::VesselTree& tree = metrics->lumen().tree();
  const long steps = run.steps();
  // The centre lines sampled every 0.5 mm, closer than neighbouring spheres (0.75 mm on the wire,
  // 0.83 mm on the catheter), where the union of the spheres is thinnest; at every step.
  const int wire_samples = 700, catheter_samples = 360;
  double deepest = 0.0;  // into the vessel's wall, of each instrument's own radius
  Vec3 wire_tip_held(0, 0, 0);  // where the wire's tip was when its hub stopped (6 s)
  for (long k = 0; k < steps; ++k) {
    const StepReport report = run.step();
    ASSERT_TRUE(report.ok) << report.message;
    if (k + 1 == 6000) wire_tip_held = wire.position(scene->state().q, 1.0);
    for (const auto& [body, samples] : {std::pair{&catheter, catheter_samples}, std::pair{&wire, wire_samples}})
      for (int i = 0; i <= samples; ++i) {
        const Vec3 x = body->position(scene->state().q, static_cast<double>(i) / samples);
        const geometry::VesselTree::Sample s = tree.sample(x, tree.maxRadius());
        if (s.branch < 0) continue;
        deepest = std::max(deepest, test::wallDepth(s, body->radius()));
      }
  }
  const auto& wire_metrics = metrics->instrument(0);
  const auto& catheter_metrics = metrics->instrument(1);
  auto branchName = [&](int branch) { return branch >= 0 ? tree.branch(branch).name : std::string("outside"); };
  const double tip_moved = (wire.position(scene->state().q, 1.0) - wire_tip_held).norm();
  std::printf("  wire: tip in %s (reached at %.2f s), %.2f mm from the target, moved %.2f mm while held; catheter: tip "
              "in %s (reached at %.2f s); deepest %.3f r; wall force max %.3f N (wire), %.3f N (catheter)\n",
              branchName(wire_metrics.branch).c_str(), wire_metrics.reached_time, 1e3 * wire_metrics.target_distance,
              1e3 * tip_moved, branchName(catheter_metrics.branch).c_str(), catheter_metrics.reached_time, deepest,
              wire_metrics.max_wall_force, catheter_metrics.max_wall_force);
  // The wire got there in the first step, while the catheter was 16 cm behind; the catheter in the
  // second, riding the held wire.
  EXPECT_EQ(branchName(wire_metrics.branch), "left_common_carotid");
  EXPECT_GT(wire_metrics.reached_time, 0.0);
  EXPECT_LT(wire_metrics.reached_time, 6.0);
  EXPECT_EQ(branchName(catheter_metrics.branch), "left_common_carotid");
  EXPECT_GT(catheter_metrics.reached_time, 6.0);
  // The catheter neither pushed the wire out nor drove it on: with its hub held, the wire's tip
  // moved by less than one of its segments (3 mm, the rod's resolution) while the catheter rode
  // 15 cm up it, and it ends within the vessel's radius (4 mm) of the target, as guidewire.json's.
  EXPECT_LT(tip_moved, 3e-3);
  EXPECT_LT(wire_metrics.target_distance, 4e-3);
  // Neither instrument went into the wall by more than a tenth of its radius (as guidewire.json's
  // tests ask), nor pushed on it beyond the scene's limit (0.5 N, where a trainer flags a push).
  EXPECT_LT(deepest, 0.1);
  EXPECT_LT(wire_metrics.max_wall_force, 0.5);
  EXPECT_LT(catheter_metrics.max_wall_force, 0.5);
  // At the end the catheter covers the wire from 16 cm (its hub: the hubs started 1 cm apart and
  // the catheter's went 15 cm further) to 34 cm (its tip, 18 cm on) of the wire's 35. Every sample
  // of that arc, two segments (6 mm) in from each end (the wire's slack behind the hub and its
  // offset from the axis in the bends shift the arc by millimetres), lies in the lumen: within
  // R_in − r of the catheter's axis, plus half the clearance, the depth beyond which the pipeline
  // redoes a step in halves (max_penetration).
  const double lumen_radius = document["nodes"][1]["components"][5]["lumen_radius"].get<double>();
  const double clearance = lumen_radius - wire.radius();
  const double wire_length = 0.35, from = 0.16 + 0.006, to = 0.34 - 0.006;
  int checked = 0;
  double farthest = 0.0;
  for (int i = 0; i <= wire_samples; ++i) {
    const double s = static_cast<double>(i) / wire_samples;
    if (s * wire_length < from || s * wire_length > to) continue;
    ++checked;
    const double distance = test::distanceToAxis(catheter, scene->state(), wire.position(scene->state().q, s));
    farthest = std::max(farthest, distance);
    EXPECT_LE(distance, 1.5 * clearance) << "wire at s = " << s;
  }
  std::printf("  the wire's %d samples under the catheter: at most %.2f clearances from its axis\n", checked,
              farthest / clearance);
  EXPECT_GT(checked, 300);  // 16.8 cm of 35 in 700 samples: 336
}

}  // namespace
}  // namespace filum
