// `filum run` end to end: bit-identical output of two runs, and a diverging scene that is
// rolled back, reported with its step and component, with every file already written intact.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "filum/run_command.hpp"
#include "support/run_scene.hpp"
#include "support/scenes.hpp"

namespace filum::app {
namespace {

namespace fs = std::filesystem;
using test::freshDirectory;
using test::runQuietly;

using test::readAll;

TEST(RunCommand, TwoRunsOfTheSameSceneAreBitIdentical) {
  const std::string scene = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/hanging_thread.json";
  const fs::path a = freshDirectory("determinism_a"), b = freshDirectory("determinism_b");
  std::string log;
  ASSERT_EQ(runQuietly(scene, a, 0.2, log), kRunOk) << log;
  ASSERT_EQ(runQuietly(scene, b, 0.2, log), kRunOk) << log;
  for (const char* file : {"control_points.csv", "curve.csv", "energy.csv", "curve.pvd", "vtk/curve_000020.vtp"}) {
    const std::string first = readAll(a / file);
    ASSERT_FALSE(first.empty()) << file;
    EXPECT_TRUE(first == readAll(b / file)) << file << " differs between two runs";
  }
  EXPECT_TRUE(fs::exists(a / "timing.json"));
}

TEST(RunCommand, TimingSaysWhereTheStepsTimeWent) {
  // knot.json has contacts and constraints: every stage took time, and the stages, exclusive,
  // add up to no more than the steps' own time (the rest: state copies and end-of-step checks).
  const std::string scene = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/knot.json";
  const fs::path dir = freshDirectory("stage_times");
  std::string log;
  ASSERT_EQ(runQuietly(scene, dir, 0.05, log), kRunOk) << log;
  const nlohmann::json timing = nlohmann::json::parse(readAll(dir / "timing.json"));
  const nlohmann::json& stages = timing.at("stages_s");
  double sum = 0.0;
  for (const char* stage : {"collision_detection", "integration", "constraint_solve", "missed_contact_check"}) {
    EXPECT_GT(stages.at(stage).get<double>(), 0.0) << stage;
    sum += stages.at(stage).get<double>();
  }
  sum += stages.at("layout").get<double>();
  // Each value is printed to 1 µs (%.6f): five of them round by 2.5 µs at most.
  EXPECT_LE(sum, timing.at("step_wall_s").get<double>() + 5e-6);
  EXPECT_NE(log.find("time by stage: collision detection"), std::string::npos) << log;
}

TEST(RunCommand, KnotCsvFollowsTheKnotOfKnotJsonAsItIsTightened) {
  // knot.json: a loose overhand knot in silk, its ends drawn 8 mm apart each from 0.02 to 0.19 s,
  // at rest until 0.35 s. knot.csv says trefoil at every frame, the thread the knot holds falls as
  // it is drawn tight, the knot rests on contacts, and its contacts slide while it is tightened,
  // far less once it rests (sticking rows damp the tangential speed by the friction rate, a
  // factor 2 per step at its default 0.5/dt: from 0.3 s, 110 steps of rest leave no trace of the
  // 7 cm/s pull).
  const std::string scene = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/knot.json";
  const fs::path dir = freshDirectory("knot_csv");
  std::string log;
  ASSERT_EQ(runQuietly(scene, dir, 0.34, log), kRunOk) << log;
  std::istringstream csv(readAll(dir / "knot.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "time,body,strand,type,throws,crossings,jones,loop_length,contacts,contact_force,slip_speed");
  double first_held = -1.0, last_held = 0.0, tightening_slip = 0.0, resting_slip = 0.0;
  int resting_contacts = 0, rows = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> f;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) f.push_back(cell);
    ASSERT_EQ(f.size(), 11u) << line;
    ++rows;
    EXPECT_EQ(f[3].substr(0, 7), "trefoil") << line;
    EXPECT_TRUE(f[4] == "+1" || f[4] == "-1") << "one single throw: " << line;
    const double t = std::stod(f[0]), held = std::stod(f[7]), slip = std::stod(f[10]);
    ASSERT_TRUE(std::isfinite(held) && std::isfinite(slip) && std::isfinite(std::stod(f[9]))) << line;
    if (first_held < 0) first_held = held;
    last_held = held;
    if (t > 0.05 && t < 0.18) tightening_slip = std::max(tightening_slip, slip);
    if (t > 0.3) {
      resting_slip = std::max(resting_slip, slip);
      resting_contacts = std::stoi(f[8]);
      EXPECT_GT(std::stod(f[9]), 0.0) << "its contacts press: " << line;
    }
  }
  EXPECT_GT(rows, 30);
  EXPECT_LT(last_held, first_held) << "drawn tight, the knot holds less thread";
  EXPECT_GT(resting_contacts, 0) << "a tied knot rests on its contacts";
  EXPECT_LT(resting_slip, 0.01 * tightening_slip);
}

TEST(RunCommand, KnotCsvSeesTheKnotWhateverTheOutputsSampling) {
  // knot.json's thread (100 control points 1 mm apart, loops of a few mm) written with 8 curve
  // samples, one every 14 mm: the output's polyline cannot hold the knot (it projects without a
  // crossing), but knot.csv samples the thread 4 times per span of its own and still says trefoil.
  const fs::path dir = freshDirectory("knot_coarse_output");
  RunOptions options;
  options.scene = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/knot.json";
  options.out = dir.string();
  options.duration = 0.01;
  options.curve_samples = 8;
  options.progress = false;
  std::ostringstream log, progress;
  ASSERT_EQ(runScene(options, log, progress), kRunOk) << log.str();
  std::istringstream curve(readAll(dir / "curve.csv"));
  std::string line;
  std::getline(curve, line);
  int first_frame_samples = 0;
  while (std::getline(curve, line) && line.rfind("0,", 0) == 0) ++first_frame_samples;
  EXPECT_EQ(first_frame_samples, 8) << "the output keeps its own sampling";
  std::istringstream knots(readAll(dir / "knot.csv"));
  std::getline(knots, line);
  int rows = 0;
  while (std::getline(knots, line)) {
    ++rows;
    EXPECT_NE(line.find(",trefoil"), std::string::npos) << line;
  }
  EXPECT_GT(rows, 1);
}

TEST(RunCommand, MetricsJsonHasTheKnotsOfTheLastFrameAsKnotCsvHasThem) {
  // instruments.json (graspers and a thread): metrics.json lists, under "knots", each strand's
  // row of knot.csv's last frame, with its type and throws.
  const fs::path dir = freshDirectory("metrics_knots");
  std::string log;
  ASSERT_EQ(runQuietly(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/instruments.json", dir, 0.05, log), kRunOk) << log;
  std::istringstream csv(readAll(dir / "knot.csv"));
  std::string line, last_time;
  std::vector<std::vector<std::string>> last_frame;
  std::getline(csv, line);
  while (std::getline(csv, line)) {
    std::vector<std::string> f;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) f.push_back(cell);
    ASSERT_EQ(f.size(), 11u) << line;  // an unknot's empty throws cell is kept: "unknot,,0"
    if (f[0] != last_time) last_frame.clear();
    last_time = f[0];
    last_frame.push_back(f);
  }
  const nlohmann::json metrics = nlohmann::json::parse(readAll(dir / "metrics.json"));
  ASSERT_TRUE(metrics.contains("knots")) << metrics.dump(2);
  const nlohmann::json& knots = metrics.at("knots");
  ASSERT_EQ(knots.size(), last_frame.size());
  ASSERT_FALSE(last_frame.empty());
  for (std::size_t i = 0; i < knots.size(); ++i) {
    EXPECT_EQ(knots[i].at("body").get<std::string>(), last_frame[i][1]);
    EXPECT_EQ(knots[i].at("type").get<std::string>(), last_frame[i][3]);
    EXPECT_EQ(knots[i].at("throws").get<std::string>(), last_frame[i][4]);
    EXPECT_EQ(knots[i].at("crossings").get<int>(), std::stoi(last_frame[i][5]));
  }
}

TEST(RunCommand, ADivergingSceneIsRolledBackReportedAndItsFilesKept) {
  // Springs 1e4 times stiffer than the demo's: ω dt ≈ 120, far past RK4's stability limit.
  test::ThreadSceneOptions o;
  o.stretch_stiffness = 1e4;
  const fs::path dir = freshDirectory("divergence");
  const fs::path scene = dir / "stiff.json";
  nlohmann::json document = test::threadScene(o);
  document["output"] = {{"interval", 1e-4}};
  std::ofstream(scene) << document.dump(2);

  std::string log;
  ASSERT_EQ(runQuietly(scene.string(), dir / "out", 0.01, log), kRunDiverged) << log;
  EXPECT_NE(log.find("diverged at step"), std::string::npos) << log;
  EXPECT_NE(log.find("(DynamicSpline)"), std::string::npos) << log;
  EXPECT_NE(log.find("/nodes/0/components/0"), std::string::npos) << log;
  EXPECT_NE(log.find("rolled back"), std::string::npos) << log;

  // Every file written so far is complete: the .pvd lists only frames that exist, every CSV
  // line is whole and finite, and the timing summary was written.
  const std::string pvd = readAll(dir / "out/curve.pvd");
  EXPECT_NE(pvd.find("</VTKFile>"), std::string::npos);
  std::istringstream lines(readAll(dir / "out/control_points.csv"));
  std::string line;
  std::getline(lines, line);
  int rows = 0;
  while (std::getline(lines, line)) {
    ++rows;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 5) << line;
    EXPECT_EQ(line.find("nan"), std::string::npos) << line;
    EXPECT_EQ(line.find("inf"), std::string::npos) << line;
  }
  EXPECT_GT(rows, 0);
  EXPECT_EQ(rows % 30, 0) << "a frame was cut short";
  EXPECT_TRUE(fs::exists(dir / "out/timing.json"));
}

TEST(RunCommand, ABadSceneIsRefusedBeforeAnythingIsWritten) {
  const fs::path dir = freshDirectory("bad_scene");
  const fs::path scene = dir / "bad.json";
  test::ThreadSceneOptions o;
  nlohmann::json document = test::threadScene(o);
  document["nodes"][0]["components"][0]["mass"] = -1.0;
  std::ofstream(scene) << document.dump(2);
  std::string log;
  EXPECT_EQ(runQuietly(scene.string(), dir / "out", 0.01, log), kRunSceneError);
  EXPECT_NE(log.find("/nodes/0/components/0/mass"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace filum::app
