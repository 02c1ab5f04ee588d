// The interaction tool (haptics/tool.hpp; the mouse probe of `filum view` and the haptic
// device's tool): its push and grasp forces pass the generic force-field test
// (forces = −∂E/∂q, analytic K and D against finite differences), its reaction on the tool is
// their opposite with the right Jacobians, a grasped point follows the tool, and a pushed
// thread leaves the sphere.
#include <gtest/gtest.h>

#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/constraints/register_components.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/haptics/tool.hpp"
#include "filum/mechanics/register_components.hpp"
#include "support/force_field_check.hpp"

namespace filum::haptics {
namespace {

using nlohmann::json;

struct ProbeScene {
  std::shared_ptr<ToolState> probe = std::make_shared<ToolState>();
  std::unique_ptr<Scene> scene;
  const ToolForceField* field = nullptr;
};

/// A straight 10 cm thread along x (no gravity), springs and damping, with the mouse probe.
ProbeScene makeScene(const std::string& integrator = "RungeKutta4") {
  ProbeScene p;
  Factory factory;
  mechanics::register_components(factory);
  constraints::register_components(factory);
  auto probe = p.probe;
  factory.add("MouseProbe", "test", [probe](const Params&) { return std::make_unique<ToolForceField>(probe); });
  const json points = {{"from", {0, 0, 0}}, {"to", {0.1, 0, 0}}, {"count", 20}};
  const json components = json::array(
      {{{"type", "DynamicSpline"}, {"control_points", points}, {"density", 910}, {"radius", 1e-4}},
       {{"type", "SpringForceField"}, {"stretch_stiffness", 1.0}, {"bend_stiffness", 1e-3}, {"damping", 1e-5}},
       {{"type", "ViscousDamping"}, {"coefficient", 2.0}},
       {{"type", "MouseProbe"}}});
  const json scene{{"name", "tool test"}, {"dt", 1e-4}, {"duration", 1.0}, {"gravity", {0, 0, 0}},
                   {"integrator", {{"type", integrator}}},
                   {"nodes", json::array({{{"name", "thread"}, {"components", components}}})}};
  p.scene = loadScene(scene, "probe test", factory);
  for (const ForceField* f : p.scene->forceFields())
    if (const auto* probe_field = dynamic_cast<const ToolForceField*>(f)) p.field = probe_field;
  return p;
}

Vec3 pointAt(const Scene& scene, double s) {
  const auto& spline = *scene.bodies().front()->curve();
  return geometry::curvePoint(spline.basis(), spline.block(scene.state().q), s);
}

TEST(InteractionTool, PushAndGrabForcesPassTheGenericForceFieldTest) {
  ProbeScene p = makeScene();
  ASSERT_NE(p.field, nullptr);
  SceneState s = p.scene->state();
  for (Eigen::Index i = 0; i < s.q.size(); ++i) s.q[i] += 1e-3 * std::sin(1.7 * i);  // not straight
  // Push: a 5 mm sphere overlapping the middle of the thread.
  p.probe->radius = 5e-3;
  p.probe->position = Vec3(0.05, 0.003, 0.001);
  p.probe->touching = true;
  test::ForceFieldCheck check;
  // Central differences (force_field_check.hpp): no sample sits within h of the sphere's rim (the
  // push's kink), so the truncation (h/ℓ)² with ℓ ≈ 1 mm the scale of the overlap is 1e-10; the
  // largest round-off is the grab's damping column, ε |F| / (h |D|): F is dominated by the 1 cm
  // spring stretch, F/D = 0.01 m · k/c = 0.01 m · ω/2 with ω = 0.5/dt, so 2.2e-16 · 0.01 · 2500 /
  // 1e-8 ≈ 5.5e-7. Twenty times that: 1e-5; a wrong term shows as O(1).
  check.h = 1e-8;
  check.tolerance = 1e-5;
  check.damping = false;  // the push has no damping: D = 0 exactly (checked below)
  const Eigen::Vector3d push = test::expectForceFieldConsistent(*p.field, s, check);
  EXPECT_GT(test::fieldForce(*p.field, s).norm(), 0.0);
  EXPECT_EQ(test::fieldJacobian(*p.field, s, 0.0, 1.0).norm(), 0.0);
  // Grab: spring–damper at the nearest point.
  ASSERT_TRUE(startGrasp(*p.probe, *p.scene, 0.01));
  // The control points are moved by up to 1 mm (1e-3 sin 1.7i), so the curve point nearest the
  // probe at x = 0.05 moves by up to 1 mm along the 0.1 m thread: 0.01 in abscissa; twice that.
  EXPECT_NEAR(p.probe->grasp.abscissa(), 0.5, 0.02);
  p.probe->position += Vec3(0.0, 0.0, 0.01);
  for (Eigen::Index i = 0; i < s.v.size(); ++i) s.v[i] = 0.01 * std::cos(0.3 * i);
  check.damping = true;
  check.gradient = false;  // the damper has no potential; the spring's is checked at v = 0 below
  const Eigen::Vector3d grab = test::expectForceFieldConsistent(*p.field, s, check);
  s.v.setZero();
  check.gradient = true;
  test::expectForceFieldConsistent(*p.field, s, check);
  std::cout << "worst relative errors: push " << push.transpose() << ", grab " << grab.transpose() << '\n';
}

TEST(InteractionTool, ItPushesEachPartOfARodAtThatPartsRadius) {
  // A straight rod along x whose second half is a thin tip ("spans": 0.4 mm against the shaft's
  // 1 mm), and a 1 mm tool 1.7 mm from its axis, right above a push sample: that is inside R + r
  // on the shaft (2 mm) and outside it on the tip (1.4 mm), so the tool pushes the shaft and
  // leaves the tip, which one radius for the rod would push too; 1.2 mm from the tip's axis it
  // pushes the tip.
  Factory factory;
  mechanics::register_components(factory);
  auto probe = std::make_shared<ToolState>();
  factory.add("MouseProbe", "test", [probe](const Params&) { return std::make_unique<ToolForceField>(probe); });
  const json rod = {{"type", "FramedChain"}, {"nodes", {{"from", {0, 0, 0}}, {"to", {0.2, 0, 0}}, {"count", 21}}},
                    {"radius", 1e-3}, {"density", 1150},
                    {"spans", {{{"from", 0.5}, {"to", 1.0}, {"radius", 4e-4}}}}};
  const json document{{"name", "tool on a rod"}, {"dt", 1e-3}, {"gravity", {0, 0, 0}},
                      {"integrator", {{"type", "ImplicitEuler"}}},
                      {"nodes", json::array({{{"name", "rod"},
                                              {"components", json::array({rod, {{"type", "MouseProbe"}}})}}})}};
  auto scene = loadScene(document, "tool on a rod", factory);
  const ToolForceField* field = nullptr;
  for (const ForceField* f : scene->forceFields())
    if (const auto* tool = dynamic_cast<const ToolForceField*>(f)) field = tool;
  ASSERT_NE(field, nullptr);
  scene->init();
  probe->radius = 1e-3;
  probe->touching = true;
  auto energyAt = [&](const Vec3& x) {
    probe->position = x;
    return field->potentialEnergy(scene->state());
  };
  // The samples: m = max(8, 4 n) at s_k = k / (m − 1), n the rod's points (tool.hpp); the tool
  // above the ones nearest x = 5 cm and 15 cm.
  const int m = std::max(8, 4 * scene->bodies().front()->curve()->pointCount());
  auto sampleX = [m](double x) { return 0.2 * std::round(x / 0.2 * (m - 1)) / (m - 1); };
  EXPECT_GT(energyAt(Vec3(sampleX(0.05), 1.7e-3, 0)), 0.0);  // the shaft
  EXPECT_EQ(energyAt(Vec3(sampleX(0.15), 1.7e-3, 0)), 0.0);  // the tip, out of reach
  EXPECT_GT(energyAt(Vec3(sampleX(0.15), 1.2e-3, 0)), 0.0);  // the tip, within 1 mm + 0.4 mm
}

TEST(InteractionTool, StiffnessIsCappedForTheExplicitStep) {
  ProbeScene p = makeScene();
  // (ω dt)² m_eff / dt²: 0.3² for the push and 0.5² for the grab.
  EXPECT_NEAR(p.field->pushStiffness(), 0.09 * p.field->effectiveMass(0.5) / 1e-8, 1e-9 * p.field->pushStiffness());
  p.probe->grasp.attach(*p.scene->bodies().front()->curve(), 0.25);
  EXPECT_NEAR(p.field->graspStiffness(), 0.25 * p.field->effectiveMass(0.25) / 1e-8, 1e-9 * p.field->graspStiffness());
  p.probe->grasp_stiffness = 1e-3;  // a softer user setting wins
  EXPECT_DOUBLE_EQ(p.field->graspStiffness(), 1e-3);
}

TEST(InteractionTool, AGrabbedPointFollowsTheProbe) {
  ProbeScene p = makeScene();
  p.probe->radius = 2e-3;
  p.probe->position = pointAt(*p.scene, 0.7) + Vec3(0.0, 0.0, 1e-3);
  p.probe->touching = true;
  ASSERT_TRUE(startGrasp(*p.probe, *p.scene, 5e-3));
  // Drag the probe 2 cm up and 1 cm sideways over 0.1 s, then hold it for 0.2 s.
  const Vec3 start = p.probe->position, goal = start + Vec3(0.0, 0.01, 0.02);
  for (int k = 1; k <= 3000; ++k) {
    p.probe->position = start + std::min(1.0, k / 1000.0) * (goal - start);
    ASSERT_TRUE(p.scene->step().ok) << "step " << k;
  }
  // The coupling lags by F/k. At the end of the hold the rest of the thread (2.9 mg) pulls on the
  // held point with at most its viscous drag c m v <= 2 s⁻¹ · 2.9e-6 kg · 0.22 m/s ≈ 1.3e-6 N,
  // against the capped grasp stiffness 0.25 m_eff/dt² (m_eff ~ 1e-7 kg: ~2.5 N/m): ~1 µm. 1 mm
  // (a twentieth of the 2.2 cm path) leaves room for the springs' pull on a bent thread and still
  // tells a held point from one left at the start.
  EXPECT_LT((pointAt(*p.scene, p.probe->grasp.abscissa()) - goal).norm(), 1e-3);
  EXPECT_LT(pointAt(*p.scene, 0.0).z(), 0.01);  // the far end lags behind: a pull, not a translation
}

TEST(InteractionTool, APushedThreadLeavesTheSphere) {
  for (const std::string integrator : {"RungeKutta4", "ImplicitEuler"}) {
    ProbeScene p = makeScene(integrator);
    p.probe->radius = 4e-3;
    p.probe->position = Vec3(0.05, 0.0, 0.0);  // centred on the thread
    p.probe->position.y() = 1e-3;              // slightly off to one side: it pushes towards −y
    p.probe->touching = true;
    for (int k = 0; k < 1000; ++k) ASSERT_TRUE(p.scene->step().ok) << integrator << " step " << k;
    const double R = p.probe->radius + (*p.scene->bodies().front()->curve()).radius();
    double deepest = 0.0;
    for (int k = 0; k <= 100; ++k) deepest = std::max(deepest, R - (pointAt(*p.scene, k / 100.0) - p.probe->position).norm());
    // At rest a sample's depth is F_k / k_p: the springs' resistance to a deflection of ~R spread
    // over the samples inside, against k_p at the explicit cap 0.09 m_eff/dt² — a few tenths of a
    // millimetre; 0.15 R (0.6 mm) bounds it, while a thread left inside or pushed through shows
    // depths of order R.
    EXPECT_LT(deepest, 0.15 * R) << integrator << ": penetration left by the penalty";
    EXPECT_LT(pointAt(*p.scene, 0.5).y(), -0.5 * R) << integrator;
  }
}

}  // namespace
}  // namespace filum::haptics

namespace filum::haptics {
namespace {

/// The force the thread exerts on the tool (the probe as p.probe holds it) at the scene state s.
Vec3 reactionAt(const ProbeScene& p, const SceneState& s) {
  ToolReaction r;
  p.field->addReaction(s, r);
  return r.force;
}

TEST(InteractionTool, TheReactionOnTheToolIsTheOppositeForceWithItsJacobians) {
  for (const bool grasping : {false, true}) {
    ProbeScene p = makeScene("ImplicitEuler");
    SceneState s = p.scene->state();
    for (Eigen::Index i = 0; i < s.q.size(); ++i) s.q[i] += 1e-3 * std::sin(1.7 * i);
    for (Eigen::Index i = 0; i < s.v.size(); ++i) s.v[i] = 0.01 * std::cos(0.3 * i);
    p.probe->radius = 5e-3;
    p.probe->position = Vec3(0.05, 0.003, 0.001);
    p.probe->velocity = Vec3(0.02, -0.01, 0.03);
    p.probe->touching = true;
    p.probe->grasp_stiffness = 900.0;  // the Touch's default coupling (implicit step: not capped)
    p.probe->grasp_damping = 0.1;
    if (grasping) {
      ASSERT_TRUE(startGrasp(*p.probe, *p.scene, 0.01));
    }
    // Action and reaction: the generalized forces on the body sum (Σ_i Q_i, the basis sums to
    // one) to minus the force on the tool.
    VecX B = VecX::Zero(s.q.size());
    p.field->addForce(s, B);
    const Vec3 on_body = p.field->body().block(B).colwise().sum().transpose();
    ToolReaction r;
    p.field->addReaction(s, r);
    EXPECT_LT((r.force + on_body).norm(), 1e-12 * on_body.norm()) << (grasping ? "grasp" : "push");
    ASSERT_GT(on_body.norm(), 0.0);
    // Jacobians against central differences in the tool's position and velocity. The forces are
    // smooth away from the sphere's rim (no sample sits on it here): the O(h²) truncation at
    // h = 1e-7 m is ~1e-14 relative, below the cancellation error ε |F| / h ≈ 1e-9 of |K| —
    // hence 1e-6 relative.
    const double h = 1e-7;
    // Column j of ∂F/∂(variable): the variable (the tool's position or velocity) moved by ±h.
    const auto column = [&](Vec3& variable, int j) {
      const Vec3 kept = variable;
      variable[j] = kept[j] + h;
      const Vec3 plus = reactionAt(p, s);
      variable[j] = kept[j] - h;
      const Vec3 minus = reactionAt(p, s);
      variable = kept;
      return Vec3((plus - minus) / (2 * h));
    };
    Eigen::Matrix3d K, D;
    for (int j = 0; j < 3; ++j) {
      K.col(j) = column(p.probe->position, j);
      D.col(j) = column(p.probe->velocity, j);
    }
    EXPECT_LT((K - r.stiffness).norm(), 1e-6 * r.stiffness.norm()) << (grasping ? "grasp" : "push") << "\n" << K << "\n" << r.stiffness;
    EXPECT_LT((D - r.damping).norm(), 1e-6 * std::max(1.0, r.damping.norm())) << (grasping ? "grasp" : "push");
  }
}

}  // namespace
}  // namespace filum::haptics
