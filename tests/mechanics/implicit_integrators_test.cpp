// The implicit integrators as scene components: what they refuse, how they recover when Newton
// does not converge, the linearized variant, and the scene files that use them.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "filum/core/scene_error.hpp"
#include "filum/mechanics/implicit_euler.hpp"
#include "support/mechanics_scenes.hpp"
#include "validation/catenary.hpp"

namespace filum {
namespace {

using nlohmann::json;

/// A force field without a Jacobian (as a user's own field might be).
class NoJacobianField final : public ForceField {
 public:
  std::string typeName() const override { return "NoJacobianField"; }
  void addForce(const SceneState&, VecX&) const override {}
};

TEST(ImplicitIntegrators, RefuseAForceFieldWithoutJacobianNamingIt) {
  Factory factory = app::makeFactory();
  factory.add("NoJacobianField", "test only", [](const Params&) { return std::make_unique<NoJacobianField>(); });
  test::ThreadSpec spec;
  for (const char* type : {"ImplicitEuler", "ImplicitMidpoint"}) {
    spec.integrator = {{"type", type}};
    try {
      loadScene(test::threadWith(spec, json::array({{{"type", "NoJacobianField"}}})), "no jacobian", factory);
      ADD_FAILURE() << type << " accepted a field without Jacobian";
    } catch (const SceneError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("/nodes/0/components/1"), std::string::npos) << message;
      EXPECT_NE(message.find("NoJacobianField"), std::string::npos) << message;
      EXPECT_NE(message.find("Jacobian"), std::string::npos) << message;
    }
  }
  // Explicit integrators do not need it.
  spec.integrator = {{"type", "RungeKutta4"}};
  EXPECT_NO_THROW(loadScene(test::threadWith(spec, json::array({{{"type", "NoJacobianField"}}})), "explicit", factory));
}

TEST(ImplicitIntegrators, RefuseBadSolverParametersWithTheirPath) {
  test::ThreadSpec spec;
  spec.integrator = {{"type", "ImplicitEuler"}, {"linear_solver", "cholesky"}};
  try {
    test::loadThreadWith(spec, json::array());
    ADD_FAILURE() << "accepted linear_solver = cholesky";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/integrator/linear_solver"), std::string::npos) << e.what();
  }
  spec.integrator = {{"type", "ImplicitMidpoint"}, {"newton_iterations", 0}};
  EXPECT_THROW(test::loadThreadWith(spec, json::array()), SceneError);
}

TEST(ImplicitIntegrators, HalveTheStepWhenNewtonDoesNotConvergeAndNeverAcceptAnUnconvergedIterate) {
  // The catenary (a real suture, no bending) released from its circular-arc start with 20 ms
  // steps: far from equilibrium, parts of the string are slack or compressed, M − h² K is
  // indefinite and Newton fails at the full step. The step is subdivided where needed; every
  // accepted step is converged, so the thread still comes to rest on the catenary.
  const validation::Catenary problem;
  validation::RunSettings settings;
  settings.control_points = 30;
  settings.dt = 2e-2;
  auto scene = validation::loadProblem(problem, settings);
  std::string failure;
  ASSERT_TRUE(validation::advance(*scene, problem.duration(), &failure)) << failure;
  const auto& solver = dynamic_cast<const mechanics::ImplicitEuler&>(scene->integrator()).solver();
  std::printf("  %ld halvings, %ld Newton solves, %ld iterations for %ld steps; error %.3e m\n", solver.halvings(),
              solver.solves(), solver.totalIterations(), scene->stepCount(), problem.error(*scene));
  EXPECT_GT(solver.halvings(), 0);
  EXPECT_LT(problem.error(*scene), 2e-4);  // as with 5 ms steps (catenary_validation_test.cpp)
}

TEST(ImplicitIntegrators, AnAttemptWhoseConstraintSolveFailsIsHalvedNotRolledBack) {
  // adaptive_suture.json with its moduli × 1000 (the stress suite's stiff1000: a 2e12 Pa suture
  // drawn onto a peg): at its 10th step the step matrix M − h²K is not definite where the thread
  // is compressed, W = L A⁻¹ Lᵀ has negative diagonal entries, and the contact solve's λ is not
  // finite. That attempt's fault belongs to it: the step is taken again in halves (where M/h²
  // outweighs the negative stiffness), and the next solves do not start from the NaN λ. Before,
  // the fault rolled the run back at that step.
  static const Factory factory = app::makeFactory();
  const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/adaptive_suture.json";
  json document = readJsonFile(path);
  for (json& component : document["nodes"][0]["components"])
    if (component.contains("youngs_modulus")) component["youngs_modulus"] = 1000.0 * component["youngs_modulus"].get<double>();
  auto scene = loadScene(document, path, factory);
  for (int k = 0; k < 30; ++k) {
    const StepReport report = scene->step();
    ASSERT_TRUE(report.ok) << "step " << k << ": " << report.message;
  }
  const auto& solver = dynamic_cast<const mechanics::ImplicitEuler&>(scene->integrator()).solver();
  EXPECT_GT(solver.halvings(), 0);
  EXPECT_TRUE(scene->state().allFinite());
}

TEST(ImplicitIntegrators, LinearizedImplicitEulerIsOneNewtonIteration) {
  // newton_iterations = 1: the scheme of Baraff & Witkin, one factorization per step, always
  // accepted; on a linear problem (quadratic bending only, no gravity) it is exact backward Euler.
  test::ThreadSpec spec;
  spec.gravity = Vec3::Zero();
  auto run = [&](int iterations) {
    spec.integrator = {{"type", "ImplicitEuler"}, {"newton_iterations", iterations}};
    auto scene = test::loadThreadWith(spec, json::array({{{"type", "ParametricBending"}, {"youngs_modulus", 2e9}}}));
    SceneState s = scene->state();
    for (int i = 0; i < scene->dofPointCount(); ++i) s.q[3 * i + 2] = 1e-3 * std::sin(31.0 * s.q[3 * i]);
    scene->setState(s);
    for (int k = 0; k < 20; ++k) EXPECT_TRUE(scene->step().ok);
    const auto& solver = dynamic_cast<const mechanics::ImplicitEuler&>(scene->integrator()).solver();
    if (iterations == 1) {
      EXPECT_EQ(solver.totalIterations(), 20);  // one linear solve per step, accepted as is
    } else {
      // The problem is linear, so the first Newton update is exact and the second one (zero to
      // round-off) confirms convergence: at most two iterations per step.
      EXPECT_GE(solver.totalIterations(), 20);
      EXPECT_LE(solver.totalIterations(), 40);
    }
    return scene->state().q;
  };
  const VecX linearized = run(1), converged = run(10);
  EXPECT_LE((linearized - converged).lpNorm<Eigen::Infinity>(), 1e-15);
}

TEST(ImplicitIntegrators, ChordMethodConvergesToTheNewtonSolution) {
  // "jacobian_update": "every_step" factors M − θh D − κh² K once per step; its iterations
  // converge linearly to the same fixed point M a = Q + Lᵀλ. After 100 steps of the released
  // cantilever both agree to the Newton tolerance accumulated over the run (1e-10 relative per
  // step: 1e-8 of the 0.2 mm deflection, asserted 1e-12 m).
  auto run = [](const char* update) {
    test::ThreadSpec spec;
    spec.control_points = 12;
    spec.length = 0.03;
    spec.mass = 2.86e-5 * 0.03;
    spec.dt = 1e-4;
    spec.integrator = {{"type", "ImplicitMidpoint"}, {"solve", "newton"}, {"jacobian_update", update}};
    auto scene = test::loadThreadWith(spec, json::array({{{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}},
                                                         {{"type", "ParametricBending"}, {"youngs_modulus", 2e9}},
                                                         {{"type", "ClampConstraint"}, {"abscissa", 0.0}}}));
    for (int k = 0; k < 100; ++k) EXPECT_TRUE(scene->step().ok);
    return scene->state().q;
  };
  EXPECT_LE((run("every_iteration") - run("every_step")).lpNorm<Eigen::Infinity>(), 1e-12);
}

TEST(ImplicitIntegrators, SceneFilesOfIssue4LoadAndRun) {
  // The scenes using the new components load, and run 20 steps without divergence.
  static const Factory factory = app::makeFactory();
  for (const char* name : {"catenary", "suture_implicit", "taut_string", "cantilever", "paper_global_stretching"}) {
    const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/" + name + ".json";
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    auto scene = loadScene(path, factory);
    for (int k = 0; k < 20; ++k) {
      const StepReport report = scene->step();
      ASSERT_TRUE(report.ok) << name << ": " << report.message;
    }
    EXPECT_LT(scene->constraintViolation(scene->state()).cwiseAbs().maxCoeff(), 1e-6) << name;
  }
}

}  // namespace
}  // namespace filum
