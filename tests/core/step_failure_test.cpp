// A numerical routine that throws during a step (a solver refusing a non-finite input, a
// resampling beyond its limit) is a fault of that step like a non-finite state: the step
// reports it with its index and time, and the state is rolled back. Never an abort.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "support/library_components.hpp"
#include "filum/core/force_field.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"

namespace filum {
namespace {

// A force field that throws from its third evaluation on, as a library routine would.
class ThrowingField final : public ForceField {
 public:
  std::string typeName() const override { return "ThrowingField"; }
  void addForce(const SceneState& s, VecX&) const override {
    if (s.steps >= 2) throw std::runtime_error("closestPoint: the query point is not finite");
  }
};

// A force field whose force turns non-finite from the third step on.
class NonFiniteField final : public ForceField {
 public:
  std::string typeName() const override { return "NonFiniteField"; }
  void addForce(const SceneState& s, VecX& B) const override {
    if (s.steps >= 2) B[0] += std::numeric_limits<double>::quiet_NaN();
  }
};

TEST(StepFailure, ANonFiniteForceNamesItsFieldAndIsRolledBack) {
  // Scene::computeForce checks the sum once per evaluation and, when it is not finite, finds the
  // field again: the report names it, not the gravity or the elastic fields before it.
  Factory factory = test::libraryComponents();
  factory.add("NonFiniteField", "a NaN force during a step (test)",
              [](const Params&) { return std::make_unique<NonFiniteField>(); });
  nlohmann::json document = readJsonFile(std::string(FILUM_TEST_DATA_DIR) + "/minimal_thread.json");
  document["nodes"][0]["components"].push_back({{"type", "NonFiniteField"}});
  auto scene = loadScene(document, "in-memory", factory);
  ASSERT_TRUE(scene->step().ok);
  ASSERT_TRUE(scene->step().ok);
  const SceneState before = scene->state();
  const StepReport report = scene->step();
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.message.find("NonFiniteField"), std::string::npos) << report.message;
  EXPECT_NE(report.message.find("produced a non-finite force"), std::string::npos) << report.message;
  EXPECT_TRUE(scene->state().q == before.q);
  EXPECT_TRUE(scene->state().v == before.v);
}

TEST(StepFailure, AnExceptionInAStepIsReportedAndRolledBack) {
  Factory factory = test::libraryComponents();
  factory.add("ThrowingField", "throws during a step (test)",
              [](const Params&) { return std::make_unique<ThrowingField>(); });
  nlohmann::json document = readJsonFile(std::string(FILUM_TEST_DATA_DIR) + "/minimal_thread.json");
  document["nodes"][0]["components"].push_back({{"type", "ThrowingField"}});
  auto scene = loadScene(document, "in-memory", factory);
  ASSERT_TRUE(scene->step().ok);
  ASSERT_TRUE(scene->step().ok);
  const SceneState before = scene->state();
  const StepReport report = scene->step();
  EXPECT_FALSE(report.ok);
  EXPECT_EQ(report.step, 2);
  EXPECT_EQ(report.time, before.time);
  EXPECT_NE(report.message.find("diverged at step 2"), std::string::npos) << report.message;
  EXPECT_NE(report.message.find("in-memory: the step failed: closestPoint: the query point is not finite"),
            std::string::npos)
      << report.message;
  EXPECT_EQ(scene->state().time, before.time);
  EXPECT_TRUE(scene->state().q == before.q);
  EXPECT_TRUE(scene->state().v == before.v);
}

}  // namespace
}  // namespace filum
