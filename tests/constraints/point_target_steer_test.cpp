// Steered targets (PointTarget::steer): an application moves a constraint's target
// between steps — a tool driven by a script, a device or Python's Scene.steer.
#include <gtest/gtest.h>

#include "filum/core/scene_error.hpp"

#include <iostream>

#include "filum/constraints/point_target.hpp"
#include "filum/constraints/target_constraint.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene.hpp"
#include "support/scenes.hpp"

namespace filum {
namespace {

TEST(PointTargetSteer, MovesAtConstantVelocityFromTheTimeItWasSteered) {
  constraints::PointTarget target = constraints::PointTarget::fixed(Vec3(1, 2, 3));
  ASSERT_TRUE(target.steer(Vec3(0.1, 0, 0), Vec3(0, 0.5, 0), 2.0));
  SceneState s;
  s.time = 2.5;
  // X(t) = x + u (t − t0): exact in binary for these values.
  EXPECT_EQ(target.position(s), Vec3(0.1, 0.25, 0));
  EXPECT_EQ(target.velocity(s), Vec3(0, 0.5, 0));
  EXPECT_EQ(target.knownAcceleration(s), Vec3::Zero());
  EXPECT_EQ(target.positionAt(3.0), Vec3(0.1, 0.5, 0));
  EXPECT_EQ(target.kind(), constraints::PointTarget::Kind::kSteered);
}

TEST(PointTargetSteer, RefusesATargetOnAnotherBody) {
  constraints::PointTarget target = constraints::PointTarget::attached("other", 0.5);
  EXPECT_FALSE(target.steer(Vec3::Zero(), Vec3::Zero(), 0.0));
  EXPECT_EQ(target.kind(), constraints::PointTarget::Kind::kAttached);
}

TEST(PointTargetSteer, AHeldEndFollowsItsSteeredTarget) {
  // A thread held at s = 0; after 0.1 s the grip is steered at u = 5 cm/s along y. The rows hold
  // g = P(0) − X(t) with critically damped Baumgarte terms (ω = 0.1 / dt = 1000/s at dt = 1e-4 s):
  // the velocity mismatch −u at the switch decays as u t e^{−ωt}, 5e-2·0.1·e^{−100} after 0.1 s
  // more, nothing; what is left is round-off of coordinates of ~0.1 m (ulp 1.4e-17 m), pulled
  // back every step by the same terms. 1e-14 m allows ~700 ulps; a target the rows did not follow
  // (or followed a step late: 5e-6 m) fails by far.
  test::ThreadSceneOptions o;
  o.viscous_damping = 0.5;
  auto scene = test::loadThreadScene(o);
  ASSERT_FALSE(scene->constraints().empty());
  auto* grip = dynamic_cast<constraints::TargetConstraint*>(scene->constraints().front());
  ASSERT_NE(grip, nullptr);
  while (scene->state().time < 0.1 - 1e-12) ASSERT_TRUE(scene->step().ok);
  const Vec3 start = grip->target().position(scene->state());
  const Vec3 u(0.0, 0.05, 0.0);
  ASSERT_TRUE(grip->target().steer(start, u, scene->state().time));
  const double t0 = scene->state().time;
  while (scene->state().time < 0.2 - 1e-12) ASSERT_TRUE(scene->step().ok);
  const Vec3 expected = start + u * (scene->state().time - t0);
  const CurveBody& body = *scene->bodies().front()->curve();
  const double error = (body.position(scene->state().q, 0.0) - expected).norm();
  std::cout << "  steered grip: |P(0) - X(t)| = " << error << " m after 5 mm of travel\n";
  EXPECT_LE(error, 1e-14);
  EXPECT_NEAR(expected.y() - start.y(), 0.005, 1e-12);
}

TEST(PointTargetSteer, AConstraintThatHasLetGoIsNotSteered) {
  // A grip that opens at 0.05 s holds nothing afterwards: steering it would move a target no
  // point follows. Accepted before the release, refused after it with the constraint's name and
  // the reason; the same for a constraint switched off.
  test::ThreadSceneOptions o;
  auto scene = test::loadThreadScene(o);
  Constraint& grip = *scene->constraints().front();
  grip.setReleaseTime(0.05);
  auto& target = dynamic_cast<constraints::TargetConstraint&>(grip).target();
  const Vec3 start = target.position(scene->state());
  EXPECT_NO_THROW(constraints::steerTarget(grip, scene->state(), start, Vec3::Zero()));
  while (scene->state().time < 0.06) ASSERT_TRUE(scene->step().ok);
  try {
    constraints::steerTarget(grip, scene->state(), start + Vec3(0.0, 0.01, 0.0), Vec3::Zero());
    FAIL() << "steering a released grip was accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(grip.describe()), std::string::npos) << what;
    EXPECT_NE(what.find("release_at"), std::string::npos) << what;
  }
  EXPECT_EQ(target.position(scene->state()), start);  // the refused steer changed nothing
  grip.setReleaseTime(std::nullopt);
  grip.setActive(false);
  EXPECT_THROW(constraints::steerTarget(grip, scene->state(), start, Vec3::Zero()), SceneError);
}

}  // namespace
}  // namespace filum
