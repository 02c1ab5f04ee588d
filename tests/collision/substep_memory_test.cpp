// Step-size memory (Scene::advanceStep): a step starts as 2^d sub-steps at the halving depth d the
// last step needed (at most 3: dt / 8), and d comes back by one level per step taken without a
// halving. Played on knot.json through its pull (0.35-0.36 s: thread dragged through the knot at
// 1 m/s, steps halved for fast slides) and the rest after it, step by step:
//   - a fresh scene starts at whole steps (d = 0);
//   - a step with no halving takes exactly 2^d sub-steps and leaves d − 1 (0 stays 0);
//   - a step with a halving leaves a deeper d (its deepest sub-step, capped at 3);
//   - the memory is used: some steps start below dt without being halved again, and the run ends
//     back at whole steps;
//   - a restored state carries its depth: the steps after it rerun bit for bit (restore_rerun_test
//     covers the state as a whole; here the depth alone).
// Exact counts, no tolerance: the rule is integer arithmetic on the scene's own counters.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "collision_scenes.hpp"

namespace filum::collision {
namespace {

const std::string kScene = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/knot.json";

long halvings(const Scene& scene) { return scene.contactHalvings() + scene.solveHalvings(); }

TEST(SubstepMemory, AStepStartsAtTheDepthTheLastOneNeededAndComesBackUp) {
  auto scene = loadScene(kScene, app::makeFactory());
  const double dt = scene->settings().dt;
  EXPECT_EQ(scene->state().memory.substep_depth, 0) << "a fresh scene takes whole steps";
  const long pull = std::lround(0.349 / dt), end = std::lround(0.45 / dt);
  for (long k = 0; k < pull; ++k) ASSERT_TRUE(scene->step().ok);
  int started_short = 0, halved = 0;
  SceneState restored;
  long restored_at = -1;
  for (long k = pull; k < end; ++k) {
    const int depth = scene->state().memory.substep_depth;
    ASSERT_GE(depth, 0);
    ASSERT_LE(depth, 3) << "the remembered depth is capped at dt / 8";
    if (restored_at < 0 && depth > 0) {
      restored = scene->state();
      restored_at = k;
    }
    const long substeps = scene->substeps(), before = halvings(*scene);
    const StepReport report = scene->step();
    ASSERT_TRUE(report.ok) << report.message;
    const long taken = scene->substeps() - substeps;
    const int next = scene->state().memory.substep_depth;
    if (halvings(*scene) == before) {
      EXPECT_EQ(taken, 1L << depth) << "step " << k << ": 2^d sub-steps at d = " << depth;
      EXPECT_EQ(next, std::max(0, depth - 1)) << "step " << k;
      if (depth > 0) ++started_short;
    } else {
      ++halved;
      EXPECT_GT(taken, 1L << depth) << "step " << k << ": a halving redoes sub-steps";
      EXPECT_GE(next, std::min(depth + 1, 3)) << "step " << k << ": a halved step leaves a deeper start (capped)";
    }
  }
  EXPECT_GT(halved, 0) << "the pull halves steps (fast slides through the knot)";
  EXPECT_GT(started_short, 0) << "steps after a halved one start short and are not halved again";
  EXPECT_EQ(scene->state().memory.substep_depth, 0) << "90 ms of rest bring it back to whole steps";

  // The depth is part of the state: a restored state reruns the same sub-steps.
  ASSERT_GE(restored_at, 0);
  const SceneState after = scene->state();
  scene->setState(restored);
  for (long k = restored_at; k < end; ++k) ASSERT_TRUE(scene->step().ok);
  EXPECT_EQ(scene->state().q, after.q) << "rerun from step " << restored_at << " is bit for bit";
}

}  // namespace
}  // namespace filum::collision
