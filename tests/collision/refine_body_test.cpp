// Control points inserted between steps (Scene::refine, CurveBody::refine: knot insertion on the
// curve's B-spline form) or removed (Scene::coarsen: knot removal within a tolerance) with
// constraints and contacts attached. Refinement changes the
// representation, not the physics:
//   - the curve is the same: P̃(s) = Σ b̃_j(s) q̃_j with q̃ = A q equals P(s) for every s;
//   - so is the velocity field Ṗ(s), and so the energy: the kinetic energy ½ ∫ m |Ṗ|² ds =
//     ½ vᵀ M v, gravity −∫ m g·P ds, and the elastic energies (integrals over s of the curve's
//     derivatives, exact by Gauss quadrature on the pieces before and after) are unchanged;
//   - constraint rows (built from the curve at the same abscissas, sliding points keep s) and
//     extra DOFs carry over, contacts are detected again on the new spheres;
//   - the motion continues: every later step succeeds and the constraints stay satisfied.
// Tolerances: each energy is a sum of at most ~10⁴ terms, each computed to a few ε (1.1e-16), so
// it changes by at most ~10⁴ · 4ε ≈ 5e-12 of the sum of the magnitudes of its kinds. The bending
// energy ½ qᵀ K q cancels: its terms are ~|q|² EI / h³ while the energy of a nearly straight
// thread is tiny, so its round-off is ~ε · n · 7 · 36 EI |q|² / h³ (7 non-zeros a row, b'' ~ 6/h²):
// 2e-13 J for sliding.json (n = 30, EI = 1.6e-7 N m², |q| = 0.1 m, h = 3.7 mm) and 1e-13 J for
// threads.json (70 points, EI = 2.4e-6 N m², |q| = 0.08 m, h = 11 mm): bound 1e-12 J on top.
// Positions are sums of d + 1 = 4 products, exact to 4ε |q| ≈ 1e-17 m for |q| ~ 0.1 m (bound
// 1e-15 m); velocities likewise to 4ε |v| (bound 1e-14 |v| + 1e-15 m/s).
#include <cmath>

#include <gtest/gtest.h>

#include "collision_scenes.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::collision {
namespace {

double energyScale(const Energy& e) { return std::abs(e.kinetic) + std::abs(e.potential); }

/// Max over 64 abscissas per body of |P(s) − P_before(s)| and |Ṗ(s) − Ṗ_before(s)|.
struct CurveSamples {
  std::vector<Vec3> positions, velocities;
};
CurveSamples sampleCurves(const Scene& scene) {
  CurveSamples out;
  for (const MechanicalState* body : scene.bodies()) {
    const CurveBody* curve = body->curve();
    for (int k = 0; k <= 64; ++k) {
      const double s = k / 64.0;
      out.positions.push_back(curve->position(scene.state().q, s));
      out.velocities.push_back(curve->position(scene.state().v, s));  // Ṗ(s) = Σ b_j(s) v_j
    }
  }
  return out;
}

void expectSameCurves(const CurveSamples& a, const CurveSamples& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i) {
    EXPECT_LE((a.positions[i] - b.positions[i]).norm(), 1e-15) << "sample " << i;
    EXPECT_LE((a.velocities[i] - b.velocities[i]).norm(), 1e-15 + 1e-14 * a.velocities[i].norm()) << "sample " << i;
  }
}

/// A reference scene of apps/scenes after `steps` steps (each must succeed).
std::unique_ptr<Scene> loadStepped(const std::string& file, long steps) {
  auto scene = loadScene(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/" + file, app::makeFactory());
  for (long k = 0; k < steps; ++k) {
    const StepReport report = scene->step();
    EXPECT_TRUE(report.ok) << file << " step " << k << ": " << report.message;
    if (!report.ok) break;
  }
  return scene;
}

/// The same curves and energies as sampled before a layout change (tolerances in the header).
void expectSameMotion(const Scene& scene, const CurveSamples& before, const Energy& e0) {
  expectSameCurves(before, sampleCurves(scene));
  const Energy e1 = scene.energy(scene.state());
  EXPECT_LE(std::abs(e1.kinetic - e0.kinetic), 5e-12 * energyScale(e0));
  EXPECT_LE(std::abs(e1.potential - e0.potential), 5e-12 * energyScale(e0) + 1e-12);
}

/// Sum of the constraints' extra DOFs (sliding abscissas), 0 when there are none.
double extraSum(const Scene& scene) {
  const Eigen::Index points = 3 * scene.dofPointCount();
  return scene.state().q.tail(scene.state().q.size() - points).sum();
}

void runRefined(const std::string& file, int body, const std::vector<double>& abscissas, long before, long after) {
  auto scene = loadStepped(file, before);
  CurveBody* curve = scene->bodies()[body]->curve();
  ASSERT_NE(curve, nullptr);
  const int points = curve->pointCount();
  const Energy e0 = scene->energy(scene->state());
  const CurveSamples s0 = sampleCurves(*scene);
  const double extra0 = extraSum(*scene);

  scene->refine(*curve, abscissas);

  EXPECT_EQ(curve->pointCount(), points + static_cast<int>(abscissas.size()));
  EXPECT_EQ(scene->layoutRevision(), 1);
  expectSameMotion(*scene, s0, e0);
  EXPECT_EQ(extra0, extraSum(*scene)) << "the constraints' extra DOFs (abscissas) are copied";

  const VecX g0 = scene->constraintViolation(scene->state());
  for (long k = 0; k < after; ++k) {
    const StepReport report = scene->step();
    ASSERT_TRUE(report.ok) << file << " step " << before + k << " after refining: " << report.message;
  }
  // The constraints stay as satisfied as they were (Baumgarte keeps the drift near where it was).
  const VecX g1 = scene->constraintViolation(scene->state());
  EXPECT_LE(g1.lpNorm<Eigen::Infinity>(), std::max(10.0 * g0.lpNorm<Eigen::Infinity>(), 1e-6)) << file;
}

TEST(RefineBody, LoopsInContactKeepTheirCurveEnergyAndContactsWhenPointsAreInserted) {
  // threads.json: eleven silicone loops held at one end, falling onto each other (unilateral
  // contacts with friction) under implicit Euler; the first loop gets three points mid-fall.
  runRefined("threads.json", 0, {0.2, 0.45, 0.8}, 150, 150);
}

TEST(RefineBody, ASutureThroughTwoSlidingHolesKeepsItsAbscissasWhenPointsAreInserted) {
  // sliding.json: a 2 GPa suture through two sliding points, its end held by a scripted grip.
  runRefined("sliding.json", 0, {0.3, 0.55, 0.6}, 100, 200);
}

TEST(RefineBody, ASceneFileSchedulesInsertionsThatHappenAtTheirTime) {
  // sliding.json with "refine": 2 points at 0.05 s, 1 at 0.1 s on the suture.
  nlohmann::json document = readJsonFile(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/sliding.json");
  nlohmann::json& spline = document["nodes"][0]["components"][0];
  ASSERT_EQ(spline["type"], "DynamicSpline");
  spline["refine"] = {{{"time", 0.05}, {"abscissas", {0.25, 0.75}}}, {{"time", 0.1}, {"abscissas", {0.6}}}};
  auto scene = loadScene(document, "sliding with refinements", app::makeFactory());
  const CurveBody* curve = scene->bodies()[0]->curve();
  const int points = curve->pointCount();
  const double dt = scene->settings().dt;
  for (long k = 0; k < std::lround(0.2 / dt); ++k) {
    const double t = scene->state().time;
    ASSERT_TRUE(scene->step().ok) << "t = " << t;
    // Applied by the step that starts at the refinement's time (within half a step).
    const int expected = points + (t > 0.05 - 0.5 * dt ? 2 : 0) + (t > 0.1 - 0.5 * dt ? 1 : 0);
    ASSERT_EQ(curve->pointCount(), expected) << "after the step from t = " << t;
  }
  EXPECT_EQ(scene->layoutRevision(), 2);
}

TEST(RefineBody, AScheduledRefinementOutsideTheCurveIsRefusedWithItsPlace) {
  nlohmann::json document = readJsonFile(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/sliding.json");
  document["nodes"][0]["components"][0]["refine"] = {{{"time", 0.05}, {"abscissas", {0.25, 1.5}}}};
  try {
    loadScene(document, "bad refinement", app::makeFactory());
    FAIL() << "an abscissa of 1.5 was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/nodes/0/components/0/refine/0/abscissas"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1.5"), std::string::npos) << e.what();
  }
}

TEST(RefineBody, AScheduledRefinementThatFailsIsTheStepsReportedFaultAndChangesNothing) {
  // The same knot five times would give it multiplicity 5 > degree + 1 = 4 (a cubic curve would
  // break apart there): knot insertion refuses it at the step of the refinement's time; that
  // step reports it (nothing is thrown out of Scene::step) and leaves the state as it was.
  nlohmann::json document = readJsonFile(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/sliding.json");
  document["nodes"][0]["components"][0]["refine"] = {{{"time", 0.0}, {"abscissas", {0.5, 0.5, 0.5, 0.5, 0.5}}}};
  auto scene = loadScene(document, "knot of multiplicity 5", app::makeFactory());
  const SceneState before = scene->state();
  const StepReport report = scene->step();
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.message.find("scheduled refinement failed"), std::string::npos) << report.message;
  EXPECT_NE(report.message.find("multiplicity"), std::string::npos) << report.message;
  EXPECT_EQ(scene->state().q, before.q);
  EXPECT_EQ(scene->state().v, before.v);
  EXPECT_EQ(scene->layoutRevision(), 0);
}

TEST(RefineBody, InsertionsBeyondTheControlPointLimitAreRefusedBeforeAnythingChanges) {
  auto scene = loadStepped("sliding.json", 1);
  CurveBody* curve = scene->bodies()[0]->curve();
  const int points = curve->pointCount();
  const std::vector<double> many(100000, 0.5);  // 1e5 more than the 1e5 limit allows
  try {
    scene->refine(*curve, many);
    FAIL() << "100,000 insertions were accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("at most 100000 control points"), std::string::npos) << e.what();
  }
  EXPECT_EQ(curve->pointCount(), points);
  EXPECT_EQ(scene->layoutRevision(), 0);
}

TEST(CoarsenBody, AJustInsertedPointComesOutExactlyAndTheMotionContinues) {
  // Removing a knot that was just inserted is exact (the curve is as smooth there as before the
  // insertion): the curve, its velocity field and its energy are those before both, to the
  // round-off of the least-squares fit (a 2 × 2 QR solve per removed point: a few ε |q|).
  auto scene = loadStepped("threads.json", 100);
  CurveBody* curve = scene->bodies()[2]->curve();
  const int points = curve->pointCount();
  const CurveSamples s0 = sampleCurves(*scene);
  const Energy e0 = scene->energy(scene->state());
  scene->refine(*curve, {0.45});
  ASSERT_TRUE(scene->coarsen(*curve, 0.45, 1e-12));
  EXPECT_EQ(curve->pointCount(), points);
  EXPECT_EQ(scene->layoutRevision(), 2);
  expectSameMotion(*scene, s0, e0);
  for (int k = 0; k < 100; ++k) ASSERT_TRUE(scene->step().ok) << "step " << k << " after coarsening";
}

TEST(CoarsenBody, ABentCurveKeepsItsPointUnlessTheToleranceAllowsTheFitAndThenMovesWithinIt) {
  // After 0.2 s of falling the loop is bent: removing its knot at s = 3/7 (uniform cubic with 10
  // points: interior knots at k/7) moves the curve. With tolerance 0 the removal is refused and
  // nothing changes; with 1 mm it is done, and every sample of the curve moves by at most the
  // convex-hull bound, which is <= the tolerance.
  auto scene = loadStepped("threads.json", 200);
  CurveBody* curve = scene->bodies()[0]->curve();
  const int points = curve->pointCount();
  const CurveSamples s0 = sampleCurves(*scene);
  EXPECT_FALSE(scene->coarsen(*curve, 3.0 / 7.0, 0.0));
  EXPECT_EQ(curve->pointCount(), points);
  EXPECT_EQ(scene->layoutRevision(), 0);
  ASSERT_TRUE(scene->coarsen(*curve, 3.0 / 7.0, 1e-3));
  EXPECT_EQ(curve->pointCount(), points - 1);
  const CurveSamples s1 = sampleCurves(*scene);
  double moved = 0.0;
  for (std::size_t i = 0; i < s0.positions.size(); ++i) moved = std::max(moved, (s1.positions[i] - s0.positions[i]).norm());
  EXPECT_GT(moved, 0.0);
  EXPECT_LE(moved, 1e-3);
  for (int k = 0; k < 100; ++k) ASSERT_TRUE(scene->step().ok) << "step " << k << " after coarsening";
}

TEST(CoarsenBody, AnAbscissaAwayFromAKnotIsRefusedWithTheBody) {
  auto scene = loadScene(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/threads.json", app::makeFactory());
  CurveBody* curve = scene->bodies()[0]->curve();
  EXPECT_THROW(scene->coarsen(*curve, 0.5, 1.0), SceneError);  // knots at k/7: 0.5 is none
  EXPECT_EQ(scene->layoutRevision(), 0);
}

TEST(RefineBody, ABasisWithoutKnotFormOrAnAbscissaOutsideTheCurveIsRefusedWithoutChange) {
  auto scene = loadScene(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/threads.json", app::makeFactory());
  CurveBody* curve = scene->bodies()[0]->curve();
  const int points = curve->pointCount();
  EXPECT_THROW(scene->refine(*curve, {1.0}), SceneError);
  EXPECT_THROW(scene->refine(*curve, {std::nan("")}), SceneError);
  EXPECT_EQ(curve->pointCount(), points);
  EXPECT_EQ(scene->layoutRevision(), 0);
  EXPECT_TRUE(scene->step().ok);
}

}  // namespace
}  // namespace filum::collision
