// Scene-file checks of the constraint components: every bad value is refused before the
// simulation starts, with the file, the JSON path and what was expected (README, "Scene
// files").
#include <gtest/gtest.h>

#include "filum/core/scene_error.hpp"
#include "support/constraint_scenes.hpp"

namespace filum {
namespace {

using nlohmann::json;

struct BadInput {
  json constraint;         // added to the thread's components
  std::string where;       // expected JSON path in the message, relative to the component
  std::string expected;    // expected fragment of the message
};

/// Loads a thread with `constraint` (at components/3: after spline, springs, damping) and a
/// node "empty" without a body; returns the error message ("" if it loaded).
std::string errorOf(const json& constraint, const json& solver = nullptr) {
  test::ConstraintThread t;
  t.constraints = {constraint};
  json document = test::constraintScene({t});
  document["nodes"].push_back({{"name", "empty"}});
  if (!solver.is_null()) document["constraint_solver"] = solver;
  try {
    test::loadConstraintScene(document);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(ConstraintParams, BadValuesAreRefusedWithTheirPlace) {
  const json fixed = {{"type", "FixedPointConstraint"}, {"abscissa", 0.5}};
  auto with = [](json base, const json& patch) {
    base.merge_patch(patch);
    return base;
  };
  const std::vector<BadInput> cases = {
      {with(fixed, {{"abscissa", 1.5}}), "/abscissa", "abscissa in [0, 1]"},
      {{{"type", "SlidingPointConstraint"}, {"abscissa", -0.1}}, "/abscissa", "abscissa in [0, 1]"},
      {{{"type", "PointOnAxisConstraint"}, {"abscissa", 0.5}, {"axis", {0, 0, 0}}}, "/axis", "non-zero"},
      {{{"type", "PointOnAxisConstraint"}, {"abscissa", 0.5}}, "/axis", "found nothing"},
      {{{"type", "PointOnPlaneConstraint"}, {"abscissa", 0.5}, {"normal", {0, 0, 0}}}, "/normal", "non-zero"},
      {{{"type", "ClampConstraint"}, {"abscissa", 0.0}, {"direction", {0, 0, 0}}}, "/direction", "non-zero"},
      {with(fixed, {{"target", {{"object", "nowhere"}, {"abscissa", 0.5}}}}), "/target/object", "known nodes: thread"},
      {with(fixed, {{"target", {{"object", "empty"}, {"abscissa", 0.5}}}}), "/target/object", "DynamicSpline"},
      {with(fixed, {{"target", {{"object", "thread"}, {"abscissa", 2.0}}}}), "/target/abscissa", "abscissa in [0, 1]"},
      {with(fixed, {{"target", {{"object", "thread"}, {"abscissa", 0.5}}}}), "/target/object", "another point"},
      {with(fixed, {{"target", {0, 0, 0}}, {"path", {{{"time", 0}, {"position", {0, 0, 0}}}}}}), "/path",
       "either 'target' or 'path'"},
      {with(fixed, {{"interpolation", "cubic"}, {"path", {{{"time", 0}, {"position", {0, 0, 0}}}}}}),
       "/interpolation", "\"linear\" or \"smooth\""},
      {with(fixed, {{"interpolation", "smooth"}}), "/interpolation", "unknown parameter"},
      {with(fixed, {{"release_at", -1.0}}), "/release_at", ">= 0"},
      {{{"type", "SpringForceField"}, {"stretch_stiffness", 1.0}, {"release_at", 1.0}}, "/release_at",
       "unknown parameter 'release_at'"},
      {{{"type", "SplineJunctionConstraint"}, {"other", "nowhere"}}, "/other", "known nodes: thread"},
      {{{"type", "SplineJunctionConstraint"}, {"other", "empty"}}, "/other", "DynamicSpline"},
      {{{"type", "SplineJunctionConstraint"}, {"other", "thread"}, {"continuity", 3}}, "/continuity", "0, 1 or 2"},
      {{{"type", "SplineJunctionConstraint"}, {"other", "thread"}, {"continuity", 1.5}}, "/continuity", "0, 1 or 2"},
      {{{"type", "SplineJunctionConstraint"}, {"other", "thread"}, {"abscissa", 0.5}, {"other_abscissa", 0.5}},
       "/other", "two different points"},
      {{{"type", "SplineJunctionConstraint"}, {"other", "thread"}, {"ratio", 0.0}}, "/ratio", "positive"},
      {{{"type", "SplineJunctionConstraint"}}, "/other", "found nothing"},
  };
  for (const BadInput& c : cases) {
    SCOPED_TRACE(c.constraint.dump());
    const std::string message = errorOf(c.constraint);
    EXPECT_NE(message.find("constraint test: /nodes/0/components/3" + c.where), std::string::npos) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
  }
}

TEST(ConstraintParams, BadSolverSettingsAreRefused) {
  const json fixed = {{"type", "FixedPointConstraint"}, {"abscissa", 0.0}};
  const std::vector<std::pair<json, std::string>> cases = {
      {{{"type", "LagrangeMultiplierSolver"}, {"drop_tolerance", 0.1}}, "/constraint_solver/drop_tolerance"},
      {{{"type", "LagrangeMultiplierSolver"}, {"sparse_solver", "magic"}}, "/constraint_solver/sparse_solver"},
      {{{"type", "LagrangeMultiplierSolver"}, {"sparse_above", -1}}, "/constraint_solver/sparse_above"},
      {{{"type", "LagrangeMultiplierSolver"}, {"contact_form", "sparse"}}, "/constraint_solver/contact_form"},
      {{{"type", "LagrangeMultiplierSolver"}, {"newton_linear_solve", "band"}}, "/constraint_solver/newton_linear_solve"},
      {{{"type", "LagrangeMultiplierSolver"}, {"newton_presweeps", -1}}, "/constraint_solver/newton_presweeps"},
      {{{"type", "LagrangeMultiplierSolver"}, {"newton_presweeps", 1001}}, "/constraint_solver/newton_presweeps"},
      {{{"type", "LagrangeMultiplierSolver"}, {"newton_chord_steps", "yes"}}, "/constraint_solver/newton_chord_steps"},
  };
  for (const auto& [solver, where] : cases) {
    const std::string message = errorOf(fixed, solver);
    EXPECT_NE(message.find("constraint test: " + where), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace filum
