// `filum run` end to end: bit-identical output of two runs, and a diverging scene that is
// rolled back, reported with its step and component, with every file already written intact.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

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
