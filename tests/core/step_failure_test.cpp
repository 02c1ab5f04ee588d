// A numerical routine that throws during a step (a solver refusing a non-finite input, a
// resampling beyond its limit) is a fault of that step like a non-finite state: the step
// reports it with its index and time, and the state is rolled back. Never an abort.
#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <string>
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

// A force field whose force turns non-finite from the third step on (with a zero Jacobian, so
// that implicit integrators take it).
class NonFiniteField final : public ForceField {
 public:
  std::string typeName() const override { return "NonFiniteField"; }
  void addForce(const SceneState& s, VecX& B) const override {
    if (s.steps >= 2) B[0] += std::numeric_limits<double>::quiet_NaN();
  }
  bool hasJacobian() const override { return true; }
  void addJacobian(const SceneState&, double, double, JacobianAccumulator&) const override {}
};

/// tests/core/data/minimal_thread.json with a `Field` added to the thread (and `integrator` in
/// place of its own, unless null), after its first two steps (which must succeed).
template <class Field>
std::unique_ptr<Scene> threadWithFieldAfterTwoSteps(const std::string& type, const nlohmann::json& integrator = nullptr) {
  Factory factory = test::libraryComponents();
  factory.add(type, "a failing field (test)", [](const Params&) { return std::make_unique<Field>(); });
  nlohmann::json document = readJsonFile(std::string(FILUM_TEST_DATA_DIR) + "/minimal_thread.json");
  document["nodes"][0]["components"].push_back({{"type", type}});
  if (!integrator.is_null()) document["integrator"] = integrator;
  auto scene = loadScene(document, "in-memory", factory);
  for (int k = 0; k < 2; ++k) {
    const StepReport report = scene->step();
    EXPECT_TRUE(report.ok) << report.message;
  }
  return scene;
}

TEST(StepFailure, ANonFiniteForceNamesItsFieldAndIsRolledBack) {
  // Scene::computeForce checks the sum once per evaluation and, when it is not finite, finds the
  // field again: the report names it, not the gravity or the elastic fields before it.
  auto scene = threadWithFieldAfterTwoSteps<NonFiniteField>("NonFiniteField");
  const SceneState before = scene->state();
  const StepReport report = scene->step();
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.message.find("NonFiniteField"), std::string::npos) << report.message;
  EXPECT_NE(report.message.find("produced a non-finite force"), std::string::npos) << report.message;
  EXPECT_TRUE(scene->state().q == before.q);
  EXPECT_TRUE(scene->state().v == before.v);
}

TEST(StepFailure, ANonFiniteForceUnderAnImplicitStepIsRolledBackWhenItsHalvesFailToo) {
  // Under ImplicitEuler a Newton attempt that meets a non-finite force is taken again in halves,
  // its fault taken back (implicit_step_solver.hpp: a wild iterate's force is the attempt's). A
  // field that is not finite at every state fails every half too: the step is still rolled back,
  // and the report still names the field and what it did.
  auto scene = threadWithFieldAfterTwoSteps<NonFiniteField>("NonFiniteField", {{"type", "ImplicitEuler"}});
  const SceneState before = scene->state();
  const StepReport report = scene->step();
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.message.find("NonFiniteField"), std::string::npos) << report.message;
  EXPECT_NE(report.message.find("produced a non-finite force"), std::string::npos) << report.message;
  EXPECT_TRUE(scene->state().q == before.q);
  EXPECT_TRUE(scene->state().v == before.v);
}

TEST(StepFailure, AnExceptionInAStepIsReportedAndRolledBack) {
  auto scene = threadWithFieldAfterTwoSteps<ThrowingField>("ThrowingField");
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
