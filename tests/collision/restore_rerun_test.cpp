// A restored state reruns exactly: after Scene::setState the run from a saved state repeats bit
// for bit the run that first left it, although the next steps read more than q and v — an
// implicit integrator's kept factorization (its linearization point and reuse schedule), the
// constraint solver's warm start, the last contacts' forces (SceneState::memory). Saved at
// instants where the kept matrix is an old one (hanging_thread.json at 1.7 s: clearing the
// caches on restore left 1.2e-6 m), with contacts (threads.json), and after the state has been
// left for another one (a restore into a scene that has moved on).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "filum/all_components.hpp"
#include "filum/constraints/target_constraint.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"

namespace filum {
namespace {

std::unique_ptr<Scene> loadShipped(const std::string& file) {
  const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/" + file;
  auto scene = loadScene(readJsonFile(path), path, app::makeFactory());
  scene->init();
  return scene;
}

void run(Scene& scene, double until) {
  while (scene.state().time < until - 0.5 * scene.settings().dt) ASSERT_TRUE(scene.step().ok) << scene.state().time;
}

/// Saves at `save`, runs to `until`; restores and reruns: the two ends must be the same bits.
void expectRerunIdentical(const std::string& file, double save, double until) {
  auto scene = loadShipped(file);
  run(*scene, save);
  const SceneState saved = scene->state();
  run(*scene, until);
  const SceneState first = scene->state();
  scene->setState(saved);
  run(*scene, until);
  EXPECT_EQ(scene->state().steps, first.steps);
  // Deterministic arithmetic (no FMA contraction, no threads in the step): equal to the bit.
  EXPECT_TRUE(scene->state().q == first.q) << file << " saved at " << save << " s: max |Δq| "
                                           << (scene->state().q - first.q).cwiseAbs().maxCoeff() << " m";
  EXPECT_TRUE(scene->state().v == first.v) << file << " saved at " << save << " s";
}

TEST(RestoreRerun, AnImplicitThreadRerunsBitForBitWhereverItWasSaved) {
  expectRerunIdentical("hanging_thread.json", 0.5, 0.6);
  expectRerunIdentical("hanging_thread.json", 1.7, 1.8);
}

TEST(RestoreRerun, ThreadsInContactRerunBitForBit) {
  // Contacts coming and going: the next detection starts from the last contacts' forces.
  expectRerunIdentical("threads.json", 1.0, 1.05);
  // A cord held on a peg: the same contact rows step after step, so the contact solve starts
  // from the last step's multipliers.
  expectRerunIdentical("capstan_held.json", 0.3, 0.35);
}

TEST(RestoreRerun, RodsInContactRerunBitForBit) {
  // The contact Newton's chord steps ride on the factorization of the step's first contact solve
  // (contact_newton.hpp): a rod lying on a table (a chord on most solves) and a wire inside a
  // catheter rerun the same, as the factorization is dropped at every step's start.
  expectRerunIdentical("framed_chain.json", 0.8, 0.85);
  expectRerunIdentical("wire_in_catheter.json", 1.0, 1.03);
}

TEST(RestoreRerun, AStateRestoredIntoAnotherSceneOfTheSameFileRerunsTheSame) {
  // The memory travels with the state: a second scene loaded from the same file, which has run
  // elsewhere, continues from the saved state as the first one did.
  auto first = loadShipped("hanging_thread.json");
  run(*first, 1.7);
  const SceneState saved = first->state();
  run(*first, 1.8);
  auto second = loadShipped("hanging_thread.json");
  run(*second, 0.3);
  second->setState(saved);
  run(*second, 1.8);
  EXPECT_TRUE(second->state().q == first->state().q)
      << "max |Δq| " << (second->state().q - first->state().q).cwiseAbs().maxCoeff() << " m";
}

TEST(RestoreRerun, AStateOfAnotherLayoutWithTheSameSizeIsRefused) {
  // A point inserted and removed again: as many coordinates as before, another layout (a basis
  // and a rest shape of their own). The saved state's step memory names its layout.
  auto scene = loadShipped("hanging_thread.json");
  run(*scene, 0.1);
  const SceneState saved = scene->state();
  CurveBody& thread = *scene->bodies().front()->curve();
  scene->refine(thread, {0.55});
  ASSERT_TRUE(scene->coarsen(thread, 0.55, 1e-3));
  ASSERT_EQ(scene->state().q.size(), saved.q.size());
  EXPECT_THROW(scene->setState(saved), SceneError);
  EXPECT_NO_THROW(scene->setState(scene->state()));  // a state of the current layout
}

TEST(RestoreRerun, ARolledBackStepLeavesTheComponentsAsTheStateWas) {
  // A step that fails is rolled back; the components' memory (the kept factorization, the warm
  // starts) goes back with the state, so running on from the rolled-back state is what a restore
  // of it gives. The grip jumps 1 m (the thread's end then moves faster than max_speed, 5 m/s:
  // the step fails) and is put back.
  const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/hanging_thread.json";
  nlohmann::json document = readJsonFile(path);
  document["max_speed"] = 5.0;
  auto scene = loadScene(document, path, app::makeFactory());
  scene->init();
  run(*scene, 0.5);
  Constraint& grip = *scene->constraints().front();
  const Vec3 held = *grip.targetPoint(scene->state());
  constraints::steerTarget(grip, scene->state(), held + Vec3(1.0, 0.0, 0.0), Vec3::Zero());
  ASSERT_FALSE(scene->step().ok);
  constraints::steerTarget(grip, scene->state(), held, Vec3::Zero());
  const SceneState rolled_back = scene->state();
  run(*scene, 0.6);
  const SceneState first = scene->state();
  scene->setState(rolled_back);
  run(*scene, 0.6);
  EXPECT_TRUE(scene->state().q == first.q)
      << "max |Δq| " << (scene->state().q - first.q).cwiseAbs().maxCoeff() << " m";
}

}  // namespace
}  // namespace filum
