// `filum run` under faults that come from outside the scene: a write that fails in the middle of
// a run (a file size limit, as on a full disk) exits 4 naming the file; a frame whose energy
// overflows while the state is finite is reported as a divergence (exit 3) and no file holds a
// non-finite value; a --duration shorter than dt / 2 is refused instead of running no step.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "filum/run_command.hpp"
#include "support/run_scene.hpp"
#include "support/scenes.hpp"

namespace filum::app {
namespace {

namespace fs = std::filesystem;
using test::freshDirectory;
using test::runQuietly;

fs::path writeScene(const fs::path& dir, const nlohmann::json& document) {
  const fs::path scene = dir / "scene.json";
  std::ofstream(scene) << document.dump(2);
  return scene;
}

// Runs the scene in a child process whose files may not grow beyond `limit` bytes
// (RLIMIT_FSIZE; SIGXFSZ ignored as `filum` does, so the write fails with EFBIG): its exit
// status, and its log through a pipe.
int runWithFileSizeLimit(const fs::path& scene, const fs::path& out, double duration, rlim_t limit, std::string& log) {
  int channel[2];
  if (pipe(channel) != 0) return -1;
  const pid_t child = fork();
  if (child == 0) {
    close(channel[0]);
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit files{limit, limit};
    setrlimit(RLIMIT_FSIZE, &files);
    std::string text;
    const int status = runQuietly(scene, out, duration, text);
    (void)!write(channel[1], text.data(), text.size());
    _exit(status);
  }
  close(channel[1]);
  char buffer[4096];
  ssize_t n = 0;
  while ((n = read(channel[0], buffer, sizeof buffer)) > 0) log.append(buffer, static_cast<std::size_t>(n));
  close(channel[0]);
  int status = 0;
  waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

TEST(RunRobustness, AWriteErrorInTheMiddleOfARunExits4NamingTheFile) {
  const fs::path dir = freshDirectory("write_error");
  test::ThreadSceneOptions o;
  nlohmann::json document = test::threadScene(o);
  document["output"] = {{"interval", 1e-3}};
  const fs::path scene = writeScene(dir, document);
  // A frame of curve.csv is 64 lines of about 100 bytes: 20 kB holds a few frames, not 50.
  std::string log;
  EXPECT_EQ(runWithFileSizeLimit(scene, dir / "out", 0.05, 20000, log), kRunIoError) << log;
  EXPECT_NE(log.find("error: " + (dir / "out").string() + "/"), std::string::npos) << log;
  EXPECT_NE(log.find(": write failed"), std::string::npos) << log;
}

TEST(RunRobustness, AnOverflowingEnergyIsADivergenceAndNothingNonFiniteIsWritten) {
  // E A = 1e308 Pa × π m² overflows: the state is finite at t = 0, its stretching energy is not.
  const fs::path dir = freshDirectory("infinite_energy");
  test::ThreadSceneOptions o;
  nlohmann::json document = test::threadScene(o);
  document["nodes"][0]["components"][0]["radius"] = 1.0;
  document["nodes"][0]["components"].push_back(
      {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 1e308}, {"rest_length", 0.05}});
  const fs::path scene = writeScene(dir, document);
  std::string log;
  EXPECT_EQ(runQuietly(scene, dir / "out", 0.01, log), kRunDiverged) << log;
  EXPECT_NE(log.find(scene.string() + ": refusing to write a non-finite energy"), std::string::npos) << log;
  // At the first step: the message points at the set-up (dt, integrator, units), not only at
  // the output that noticed.
  EXPECT_NE(log.find("likely cause: "), std::string::npos) << log;
  EXPECT_NE(log.find("wrong units"), std::string::npos) << log;
  EXPECT_NE(log.find("filum check " + scene.string()), std::string::npos) << log;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "out")) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str().find("nan"), std::string::npos) << entry.path();
    EXPECT_EQ(text.str().find("inf"), std::string::npos) << entry.path();
  }
}

TEST(RunRobustness, ADurationShorterThanHalfAStepIsRefused) {
  const fs::path dir = freshDirectory("short_duration");
  test::ThreadSceneOptions o;
  o.dt = 1e-3;
  const fs::path scene = writeScene(dir, test::threadScene(o));
  std::string log;
  EXPECT_EQ(runQuietly(scene, dir / "out", 1e-4, log), kRunSceneError) << log;
  EXPECT_NE(log.find(scene.string() + ": /dt (with --duration"), std::string::npos) << log;
  EXPECT_NE(log.find("shorter than dt / 2"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace filum::app
