// The headless haptic demo (apps/scenes/haptic_grasp.json) end to end: the scripted
// Phantom's jaws close on the real suture where the stylus is, the thread pulled taut pushes
// back with the tension of the thread and the coupling in series, the forces the device gets
// stay within its limits, haptics.csv has every servo tick, and a run is bit-identical to the
// next. Errors in the "haptics" block name their JSON path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "filum/all_components.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/haptics/haptic_session.hpp"
#include "filum/haptics/interrupt.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/run_command.hpp"
#include "support/run_scene.hpp"

namespace filum::app {
namespace {

namespace fs = std::filesystem;

const std::string kScene = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/haptic_grasp.json";

using test::readAll;

TEST(HapticSession, TheJawsHoldTheThreadAndTheTautThreadPullsBack) {
  const nlohmann::json document = readJsonFile(kScene);
  auto scene = loadScene(document, kScene, makeFactory());
  auto session = haptics::HapticSession::fromScene(document, kScene, *scene, scene->settings().duration);
  ASSERT_NE(session, nullptr);
  session->start();
  double grasp_abscissa = -1.0;
  Vec3 held_force = Vec3::Zero(), held_stylus = Vec3::Zero();
  const long steps = std::lround(scene->settings().duration / scene->settings().dt);
  for (long k = 1; k <= steps; ++k) {
    session->beforeStep(*scene);
    ASSERT_TRUE(scene->step().ok) << "step " << k;
    session->afterStep(*scene);
    const double t = scene->state().time;
    if (session->tool().grasping) grasp_abscissa = session->tool().grasp.abscissa();
    if (std::abs(t - 1.15) < 0.5e-3) {  // taut and still (0.8 s to 1.2 s)
      held_stylus = session->tool().position;
      ASSERT_TRUE(session->tool().grasping);
      held_force = session->servo().log().back().commanded;
    }
  }
  session->finish();
  // The jaws closed 9 cm down the 10 cm thread (the stylus 0.8 mm beside it, at z = −9 cm).
  EXPECT_NEAR(grasp_abscissa, 0.9, 0.01);
  // Taut: the thread (EA / L*, EA = 2 GPa · π (0.1 mm)² = 62.8 N) and the coupling (k = 900 N/m)
  // in series carry F = k_s (|X| − L*), k_s = k k_t / (k + k_t), along the line to the fixed
  // end. The thread's Green–Lagrange law differs from the linear EA ε by O(ε) (ε = F/EA ≈ 1.5 % here),
  // gravity on 2.9 mg adds 3e-5 N and the bending stiffness of the bend at the jaws a little
  // more: 5 % of F covers them.
  const double L = 0.1 * grasp_abscissa, EA = 2e9 * M_PI * 1e-8;
  const double k_t = EA / L, k = session->coupling().stiffness, k_s = k * k_t / (k + k_t);
  const double expected = k_s * (held_stylus.norm() - L);
  ASSERT_GT(expected, 0.1);  // the scene pulls the thread well taut
  // The commanded force is in the device frame ("y_up": scene z is device y); its size is frame-free.
  EXPECT_NEAR(held_force.norm(), expected, 0.05 * expected) << "stylus " << held_stylus.transpose();
  // ... and it pulls the hand back toward the fixed end (device frame: scene (x, y, z) = (x, −z_d, y_d)).
  const Vec3 toward_end_scene = -held_stylus.normalized();
  const Vec3 toward_end_device(toward_end_scene.x(), toward_end_scene.z(), -toward_end_scene.y());
  EXPECT_GT(held_force.normalized().dot(toward_end_device), 0.99);
  // Every force sent is finite and within the Touch's limits, and the device ends at zero force.
  for (const haptics::ServoSample& s : session->servo().log()) {
    ASSERT_TRUE(s.sent.allFinite());
    EXPECT_LE(s.sent.norm(), 3.3 + 1e-12);
  }
  EXPECT_EQ(session->servo().log().back().sent, Vec3::Zero());  // released and away at the end
}

TEST(HapticSession, TheDemoRunWritesEveryServoTickAndIsBitIdentical) {
  const fs::path a = test::freshDirectory("haptic_a"), b = test::freshDirectory("haptic_b");
  std::string log;
  ASSERT_EQ(test::runQuietly(kScene, a, 1.6, log), kRunOk) << log;
  ASSERT_EQ(test::runQuietly(kScene, b, 1.6, log), kRunOk) << log;
  EXPECT_NE(log.find("haptics: ScriptedDevice"), std::string::npos) << log;
  const std::string csv = readAll(a / "haptics.csv");
  EXPECT_EQ(csv, readAll(b / "haptics.csv"));
  // One row per tick: ticks at 0, 1, ..., 1599 ms (the last step starts at 1.599 s).
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 1600);
  EXPECT_EQ(csv.find("nan"), std::string::npos);
}

TEST(HapticSession, AnAttachedThreadEndFollowsTheStylus) {
  nlohmann::json document = readJsonFile(kScene);
  document["haptics"]["tool"] = {{"type", "Attachment"}, {"object", "thread"}, {"abscissa", 1.0}};
  // Device frame y_up, origin at scene (0, 0, −0.09): the thread's end (0, 0, −0.1) is device
  // (0, −0.01, 0); the stylus carries it 2 cm sideways and 5 mm up in 0.5 s (the thread stays
  // slack: 9.7 cm from the top end), then holds still.
  document["haptics"]["device"]["waypoints"] = {{{"time", 0.0}, {"position", {0.0, -0.01, 0.0}}},
                                                {{"time", 0.5}, {"position", {0.02, -0.005, 0.0}}}};
  auto scene = loadScene(document, kScene, makeFactory());
  auto session = haptics::HapticSession::fromScene(document, kScene, *scene, 0.6);
  session->start();
  for (int k = 1; k <= 600; ++k) {
    session->beforeStep(*scene);
    ASSERT_TRUE(scene->step().ok) << "step " << k;
    session->afterStep(*scene);
  }
  session->finish();
  const MechanicalState& thread = *scene->bodies().front();
  const Vec3 end = geometry::curvePoint(thread.curve()->basis(), thread.block(scene->state().q), 1.0);
  // At rest the coupling carries only the slack thread's pull on its end (its weight, 2.8e-5 N,
  // and the bending of the slack, of the same order): k = 900 N/m stretches by ~1e-7 m. 0.1 s
  // after the stop the swing has settled under the coupling's damping. 0.1 mm is 0.5 % of the
  // 2 cm carried, far above both.
  EXPECT_LT((end - Vec3(0.02, 0.0, -0.095)).norm(), 1e-4) << end.transpose();
}

TEST(HapticSession, CtrlCStopsTheRunWithTheForcesOff) {
  const fs::path out = test::freshDirectory("haptic_interrupted");
  haptics::installInterruptHandler();
  std::raise(SIGINT);  // as if pressed before the first tick
  std::string log;
  const int status = test::runQuietly(kScene, out, 1.6, log);
  haptics::clearInterrupt();
  EXPECT_EQ(status, kRunInterrupted) << log;
  EXPECT_NE(log.find("interrupted (Ctrl-C)"), std::string::npos) << log;
  // The run stopped after its first step, and haptics.csv says nothing was sent.
  const std::string csv = readAll(out / "haptics.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1) << csv;  // the header only: no tick ran
}

TEST(HapticSession, ErrorsNameTheirPathInTheHapticsBlock) {
  nlohmann::json document = readJsonFile(kScene);
  const auto expectError = [&](const nlohmann::json& changed, const std::string& where) {
    auto scene = loadScene(changed, "grasp.json", makeFactory());
    try {
      haptics::HapticSession::fromScene(changed, "grasp.json", *scene, 1.0);
      ADD_FAILURE() << "no error for " << where;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("grasp.json: " + where), std::string::npos) << e.what();
    }
  };
  nlohmann::json bad = document;
  bad["haptics"]["device"]["type"] = "Falcon";
  expectError(bad, "/haptics/device/type");
  bad = document;
  bad["haptics"]["coupling"] = {{"stiffness", 4000}};
  expectError(bad, "/haptics/coupling/stiffness");
  bad = document;
  bad["haptics"]["tool"] = {{"type", "Attachment"}, {"object", "needle"}, {"abscissa", 1.0}};
  expectError(bad, "/haptics/tool/object");
  bad = document;
  bad["haptics"]["rate"] = 50;
  expectError(bad, "/haptics/rate");
  bad = document;
  bad["haptics"]["device"]["waypoints"][1]["time"] = 0.0;  // not after the first
  expectError(bad, "/haptics/device/waypoints/1/time");
  bad = document;
  bad["haptics"]["frame"]["rotation"] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 2}};
  expectError(bad, "/haptics/frame/rotation");
}

}  // namespace
}  // namespace filum::app
