// The contact response as the pipeline applies it: the penalty forces' analytic Jacobian against
// finite differences, an implicit integrator resting a thread on a plane with it, exact
// save/restore and determinism with contacts, the probe pushing a thread (and feeling it), and
// the obstacles' signed distances.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include <iostream>

#include "collision_scenes.hpp"
#include "filum/collision/capsule_obstacle.hpp"
#include "filum/collision/implicit_surface_obstacle.hpp"
#include "filum/collision/plane_obstacle.hpp"
#include "filum/collision/probe_sphere.hpp"
#include "filum/collision/sphere_obstacle.hpp"

namespace filum::collision {
namespace {

/// Two threads crossing (B 1.8 mm above A, radius 1 mm: 0.2 mm interpenetration), A also
/// pressed 0.2 mm into a plane with friction.
nlohmann::json pressedThreads(const std::string& integrator = "RungeKutta4") {
  test::CollisionThread a;
  a.name = "a";
  a.control_points = {{"from", {-0.03, 0.0, 0.0008}}, {"to", {0.03, 0.0, 0.0008}}, {"count", 8}};
  test::CollisionThread b = a;
  b.name = "b";
  b.control_points = {{"from", {0.0, -0.03, 0.0026}}, {"to", {0.0, 0.03, 0.0026}}, {"count", 8}};
  const nlohmann::json pipeline = {{"type", "ContactPipeline"}, {"stiffness", 200.0}, {"damping", 0.01},
                                   {"friction", 0.4}, {"friction_velocity", 1e-3}};
  const nlohmann::json plane = {{"type", "PlaneObstacle"}, {"normal", {0, 0, 1}}, {"friction", 0.6}};
  nlohmann::json scene = test::collisionScene({a, b}, pipeline, 1e-4, nlohmann::json::array({plane}));
  scene["integrator"] = {{"type", integrator}};
  return scene;
}

VecX contactForce(const CollisionPipeline& pipeline, const SceneState& s) {
  VecX B = VecX::Zero(s.q.size());
  pipeline.addForce(s, B);
  return B;
}

TEST(PenaltyContact, AnalyticJacobianMatchesFiniteDifferences) {
  auto scene = test::loadCollisionScene(pressedThreads());
  CollisionPipeline& pipeline = *scene->collisionPipeline();
  SceneState s = scene->state();
  // Velocities of a few mm/s: some contacts slide (|v_t| > ε), some are in the viscous regime.
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-3e-3, 3e-3);
  for (Eigen::Index i = 0; i < s.v.size(); ++i) s.v[i] = u(rng);
  pipeline.beginStep(*scene, s, scene->settings().dt);
  ASSERT_GT(test::pipelineOf(*scene).statistics().thread_contacts, 0);
  ASSERT_GT(test::pipelineOf(*scene).statistics().obstacle_contacts, 0);
  const Eigen::Index n = s.q.size();
  for (const auto& [k_factor, d_factor, h] : {std::tuple{1.0, 0.0, 1e-8}, std::tuple{0.0, 1.0, 1e-8}}) {
    Triplets triplets;
    TripletAccumulator accumulator(triplets);
    pipeline.addJacobian(s, k_factor, d_factor, accumulator);
    Eigen::SparseMatrix<double> J(n, n);
    J.setFromTriplets(triplets.begin(), triplets.end());
    const MatX analytic(J);
    MatX fd(n, n);
    for (Eigen::Index j = 0; j < n; ++j) {
      SceneState p = s, m = s;
      (k_factor > 0 ? p.q : p.v)[j] += h;
      (k_factor > 0 ? m.q : m.v)[j] -= h;
      fd.col(j) = (contactForce(pipeline, p) - contactForce(pipeline, m)) / (2 * h);
    }
    // Central differences: truncation h²/6 |F'''| and round-off ε|F|/h, both below 1e-6 of the
    // largest entry here — unless a step crosses a kink of the law (f_n = 0, |v_t| = ε), which the
    // random state avoids.
    const double error = (analytic - fd).cwiseAbs().maxCoeff() / fd.cwiseAbs().maxCoeff();
    EXPECT_LT(error, 1e-6) << (k_factor > 0 ? "stiffness" : "damping");
  }
}

TEST(PenaltyContact, ImplicitEulerRestsAThreadOnAPlane) {
  // A thread dropped 2 mm onto a plane under implicit Euler (dt = 1 ms, ten times the explicit
  // scenes' step) comes to rest on it: the gap of every contact ends near −m g/(k·contacts).
  test::CollisionThread t;
  t.control_points = {{"from", {-0.03, 0.0, 0.003}}, {"to", {0.03, 0.0, 0.003}}, {"count", 8}};
  t.viscous_damping = 5.0;
  const nlohmann::json pipeline = {{"type", "ContactPipeline"}, {"stiffness", 200.0}, {"damping", 0.05}, {"friction", 0.3}};
  const nlohmann::json plane = {{"type", "PlaneObstacle"}, {"normal", {0, 0, 1}}};
  nlohmann::json document = test::collisionScene({t}, pipeline, 1e-3, nlohmann::json::array({plane}));
  document["integrator"] = {{"type", "ImplicitEuler"}};
  auto scene = test::loadCollisionScene(document);
  for (int k = 0; k < 1000; ++k) ASSERT_TRUE(scene->step().ok) << "step " << k;
  const auto& centers = test::pipelineOf(*scene).models().front()->centers();
  const int K = test::pipelineOf(*scene).models().front()->sphereCount();
  const double lowest = centers.topRows(K).col(2).minCoeff(), highest = centers.topRows(K).col(2).maxCoeff();
  // 1e-4 kg on K ≈ 61 spheres, k = 200 N/m each: the mean static penetration is
  // δ = m g/(k K) ≈ 8e-8 m, so the centres rest at r − δ = 1e-3 m − δ. The load is not spread
  // evenly (the end spheres carry the spline's end mass, more or less than the mean), but each
  // sphere's share lies between 0 and 2 m g / K: every centre is within δ of r − δ. (Asserted
  // 2e-5 m before, 250 δ.)
  const double delta = 1e-4 * 9.81 / (200.0 * K);
  std::cout << "  resting centres: " << lowest << " .. " << highest << " m (r - delta = " << 1e-3 - delta << " m)\n";
  EXPECT_NEAR(lowest, 1e-3 - delta, delta);
  EXPECT_NEAR(highest, 1e-3 - delta, delta);
  EXPECT_LT(scene->state().v.cwiseAbs().maxCoeff(), 1e-4);
}

TEST(ContactPipeline, SaveRestoreAndReplaysAreBitIdentical) {
  for (const std::string response : {"penalty", "unilateral"}) {
    nlohmann::json document = pressedThreads();
    document["collision"]["response"] = response;
    auto first = test::loadCollisionScene(document);
    auto second = test::loadCollisionScene(document);
    // Every step must succeed: runs rolled back at the same step would also compare equal.
    for (int k = 0; k < 100; ++k) {
      ASSERT_TRUE(first->step().ok) << response << " step " << k;
      ASSERT_TRUE(second->step().ok) << response << " step " << k;
    }
    const SceneState saved = first->state();
    for (int k = 0; k < 100; ++k) ASSERT_TRUE(first->step().ok) << response << " step " << 100 + k;
    const SceneState after = first->state();
    ASSERT_EQ(after.steps, 200) << response;
    // The replica ran the same steps: identical to the bit.
    for (int k = 0; k < 100; ++k) ASSERT_TRUE(second->step().ok) << response << " step " << 100 + k;
    EXPECT_EQ(second->state().q, after.q) << response;
    EXPECT_EQ(second->state().v, after.v) << response;
    // Restored to step 100, the same 100 steps again give the same state: the contact set
    // depends on the state only.
    first->setState(saved);
    for (int k = 0; k < 100; ++k) ASSERT_TRUE(first->step().ok) << response << " replayed step " << 100 + k;
    EXPECT_EQ(first->state().q, after.q) << response;
    EXPECT_EQ(first->state().v, after.v) << response;
  }
}

class Probe : public ::testing::TestWithParam<std::string> {};

TEST_P(Probe, TheScriptedProbePushesAThreadAndFeelsItsReaction) {
  // A thread along x resting on a plane with friction; a 5 mm probe comes along +y from the side
  // and sweeps 2 cm through the thread's middle at 0.2 m/s: the thread is dragged along +y, and
  // the force on the probe points back along −y (friction on the plane resists the drag).
  test::CollisionThread t;
  t.control_points = {{"from", {-0.05, 0.0, 0.001}}, {"to", {0.05, 0.0, 0.001}}, {"count", 12}};
  const nlohmann::json plane = {{"type", "PlaneObstacle"}, {"normal", {0, 0, 1}}, {"friction", 0.5}};
  const nlohmann::json probe = {{"type", "ProbeSphere"}, {"radius", 0.005},
                                {"path", {{{"time", 0.0}, {"position", {0.0, -0.01, 0.003}}},
                                          {{"time", 0.15}, {"position", {0.0, 0.02, 0.003}}}}}};
  const nlohmann::json pipeline = {{"type", "ContactPipeline"}, {"response", GetParam()}, {"stiffness", 200.0}, {"damping", 0.01}};
  auto scene = test::loadCollisionScene(test::collisionScene({t}, pipeline, 1e-4, nlohmann::json::array({plane, probe})));
  const auto& p = test::pipelineOf(*scene);
  ASSERT_EQ(p.obstacles().size(), 2u);
  Vec3 felt = Vec3::Zero();
  double strongest = 0.0;
  for (int k = 0; k < 1200; ++k) {  // 0.12 s: the probe has gone 2.4 cm
    ASSERT_TRUE(scene->step().ok);
    felt = p.obstacleForce(1, scene->state());
    if (felt.norm() > 0.0) {
      EXPECT_LT(felt.y(), 0.0) << "step " << k;
    }
    strongest = std::max(strongest, -felt.y());
  }
  const auto& probe_model = dynamic_cast<const ProbeSphere&>(*p.obstacles()[1]);
  EXPECT_NEAR(probe_model.center().y(), -0.01 + 0.2 * 0.12 - 0.2 * 1e-4, 1e-9);
  // The middle of the thread went ahead of the probe: at least its centre + radii along +y.
  const auto& model = *p.models().front();
  const int middle = model.sphereCount() / 2;
  EXPECT_GT(model.centers()(middle, 1), probe_model.center().y() + 0.005 + 0.001 - 5e-4);
  EXPECT_GT(strongest, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Responses, Probe, ::testing::Values("penalty", "unilateral"));

TEST(Obstacles, SignedDistancesOfAnalyticAndImplicitSurfaces) {
  SurfaceSample s;
  const PlaneObstacle plane(Vec3(0, 0, 1), Vec3(0, 0, 2));
  ASSERT_TRUE(plane.sample(Vec3(3, 4, 0.5), 1.0, s));
  EXPECT_DOUBLE_EQ(s.distance, -0.5);
  EXPECT_FALSE(plane.sample(Vec3(0, 0, 3), 1.0, s));

  const SphereObstacle ball(Vec3(1, 0, 0), 0.5);
  ASSERT_TRUE(ball.sample(Vec3(1, 0, 0.7), 1.0, s));
  EXPECT_NEAR(s.distance, 0.2, 1e-15);
  EXPECT_LT((s.normal - Vec3::UnitZ()).norm(), 1e-15);

  const CapsuleObstacle capsule(Vec3(0, 0, 0), Vec3(1, 0, 0), 0.1);
  ASSERT_TRUE(capsule.sample(Vec3(0.5, 0.3, 0), 1.0, s));
  EXPECT_NEAR(s.distance, 0.2, 1e-15);
  ASSERT_TRUE(capsule.sample(Vec3(-0.3, 0, 0), 1.0, s));  // beyond the end cap
  EXPECT_NEAR(s.distance, 0.2, 1e-15);

  // Convolution surface around a long straight skeleton: a tube of radius R (its iso-value is
  // set for that, convolution_surface.hpp). The first-order distance f/|∇f| is exact on the
  // surface and accurate to O(d²) near it: at 10 % of R off the surface, within 1 % of R.
  Points skeleton(2, 3);
  skeleton << -1, 0, 0, 1, 0, 0;
  const double R = 0.01;
  const ImplicitSurfaceObstacle tube(skeleton, R, 0.0);
  for (double d : {-0.1 * R, 0.0, 0.1 * R}) {
    ASSERT_TRUE(tube.sample(Vec3(0.0, 0.0, R + d), 1.0, s));
    EXPECT_NEAR(s.distance, d, 0.01 * R) << d;
    EXPECT_LT((s.normal - Vec3::UnitZ()).norm(), 1e-9);
  }
  EXPECT_FALSE(tube.sample(Vec3(0, 0, 0.5), 0.01, s));
}

}  // namespace
}  // namespace filum::collision
