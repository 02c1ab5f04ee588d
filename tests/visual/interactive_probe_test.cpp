// The mouse probe of `filum view` (issue 7): its push and grab forces pass the generic
// force-field test (forces = −∂E/∂q, analytic K and D against finite differences), a grabbed
// point follows the probe, and a pushed thread leaves the sphere.
#include <gtest/gtest.h>

#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/visual/interactive_probe.hpp"
#include "support/force_field_check.hpp"
#include "visual/visual_test_support.hpp"

namespace filum::visual {
namespace {

using nlohmann::json;

struct ProbeScene {
  std::shared_ptr<ProbeState> probe = std::make_shared<ProbeState>();
  std::unique_ptr<Scene> scene;
  const ProbeForceField* field = nullptr;
};

/// A straight 10 cm thread along x (no gravity), springs and damping, with the mouse probe.
ProbeScene makeScene(const std::string& integrator = "RungeKutta4") {
  ProbeScene p;
  Factory factory = test::visualFactory();
  auto probe = p.probe;
  factory.add("MouseProbe", "test", [probe](const Params&) { return std::make_unique<ProbeForceField>(probe); });
  json points = {{"from", {0, 0, 0}}, {"to", {0.1, 0, 0}}, {"count", 20}};
  json scene = test::splineScene(points, json::array({{{"type", "SpringForceField"}, {"stretch_stiffness", 1.0},
                                                       {"bend_stiffness", 1e-3}, {"damping", 1e-5}},
                                                      {{"type", "ViscousDamping"}, {"coefficient", 2.0}},
                                                      {{"type", "MouseProbe"}}}),
                                 1e-4);
  scene["nodes"][0]["components"][0].erase("mass");
  scene["nodes"][0]["components"][0]["density"] = 910;
  scene["integrator"] = {{"type", integrator}};
  p.scene = loadScene(scene, "probe test", factory);
  for (const ForceField* f : p.scene->forceFields())
    if (const auto* probe_field = dynamic_cast<const ProbeForceField*>(f)) p.field = probe_field;
  return p;
}

Vec3 pointAt(const Scene& scene, double s) {
  const auto& spline = static_cast<const mechanics::DynamicSpline&>(*scene.bodies().front());
  return geometry::curvePoint(spline.basis(), spline.block(scene.state().q), s);
}

TEST(InteractiveProbe, PushAndGrabForcesPassTheGenericForceFieldTest) {
  ProbeScene p = makeScene();
  ASSERT_NE(p.field, nullptr);
  SceneState s = p.scene->state();
  for (Eigen::Index i = 0; i < s.q.size(); ++i) s.q[i] += 1e-3 * std::sin(1.7 * i);  // not straight
  // Push: a 5 mm sphere overlapping the middle of the thread.
  p.probe->radius = 5e-3;
  p.probe->position = Vec3(0.05, 0.003, 0.001);
  p.probe->touching = true;
  test::ForceFieldCheck check;
  check.h = 1e-8;
  check.tolerance = 1e-5;
  check.damping = false;  // the push has no damping: D = 0 exactly (checked below)
  const Eigen::Vector3d push = test::expectForceFieldConsistent(*p.field, s, check);
  EXPECT_GT(test::fieldForce(*p.field, s).norm(), 0.0);
  EXPECT_EQ(test::fieldJacobian(*p.field, s, 0.0, 1.0).norm(), 0.0);
  // Grab: spring–damper at the nearest point.
  ASSERT_TRUE(startGrab(*p.probe, *p.scene, 0.01));
  EXPECT_NEAR(p.probe->grab_abscissa, 0.5, 0.02);
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

TEST(InteractiveProbe, StiffnessIsCappedForTheExplicitStep) {
  ProbeScene p = makeScene();
  // (ω dt)² m_eff / dt²: 0.3² for the push and 0.5² for the grab.
  EXPECT_NEAR(p.field->pushStiffness(), 0.09 * p.field->effectiveMass(0.5) / 1e-8, 1e-9 * p.field->pushStiffness());
  p.probe->grab_abscissa = 0.25;
  EXPECT_NEAR(p.field->grabStiffness(), 0.25 * p.field->effectiveMass(0.25) / 1e-8, 1e-9 * p.field->grabStiffness());
  p.probe->grab_stiffness = 1e-3;  // a softer user setting wins
  EXPECT_DOUBLE_EQ(p.field->grabStiffness(), 1e-3);
}

TEST(InteractiveProbe, AGrabbedPointFollowsTheProbe) {
  ProbeScene p = makeScene();
  p.probe->radius = 2e-3;
  p.probe->position = pointAt(*p.scene, 0.7) + Vec3(0.0, 0.0, 1e-3);
  p.probe->touching = true;
  ASSERT_TRUE(startGrab(*p.probe, *p.scene, 5e-3));
  // Drag the probe 2 cm up and 1 cm sideways over 0.1 s, then hold it for 0.2 s.
  const Vec3 start = p.probe->position, goal = start + Vec3(0.0, 0.01, 0.02);
  for (int k = 1; k <= 3000; ++k) {
    p.probe->position = start + std::min(1.0, k / 1000.0) * (goal - start);
    ASSERT_TRUE(p.scene->step().ok) << "step " << k;
  }
  EXPECT_LT((pointAt(*p.scene, p.probe->grab_abscissa) - goal).norm(), 1e-3);
  EXPECT_LT(pointAt(*p.scene, 0.0).z(), 0.01);  // the far end lags behind: a pull, not a translation
}

TEST(InteractiveProbe, APushedThreadLeavesTheSphere) {
  for (const std::string integrator : {"RungeKutta4", "ImplicitEuler"}) {
    ProbeScene p = makeScene(integrator);
    p.probe->radius = 4e-3;
    p.probe->position = Vec3(0.05, 0.0, 0.0);  // centred on the thread
    p.probe->position.y() = 1e-3;              // slightly off to one side: it pushes towards −y
    p.probe->touching = true;
    for (int k = 0; k < 1000; ++k) ASSERT_TRUE(p.scene->step().ok) << integrator << " step " << k;
    const double R = p.probe->radius + static_cast<const mechanics::DynamicSpline&>(*p.scene->bodies().front()).radius();
    double deepest = 0.0;
    for (int k = 0; k <= 100; ++k) deepest = std::max(deepest, R - (pointAt(*p.scene, k / 100.0) - p.probe->position).norm());
    EXPECT_LT(deepest, 0.15 * R) << integrator << ": penetration left by the penalty";
    EXPECT_LT(pointAt(*p.scene, 0.5).y(), -0.5 * R) << integrator;
  }
}

}  // namespace
}  // namespace filum::visual
