// PointLoad (point_load.hpp) on a spline and on a rod, and RodEndFrame's refusals: what reaches
// the control points and frames, the path in time, and bad input refused with its place.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/mechanics/point_load.hpp"
#include "support/mechanics_scenes.hpp"

namespace filum {
namespace {

using nlohmann::json;

std::unique_ptr<Scene> threadWithLoad(const json& load) {
  test::ThreadSpec spec;
  spec.gravity.setZero();
  auto scene = test::loadThreadWith(spec, json::array({load}));
  scene->init();
  return scene;
}

VecX loadForces(const Scene& scene, double time) {
  SceneState s = scene.state();
  s.time = time;
  VecX B = VecX::Zero(scene.velocitySize());
  for (const ForceField* field : scene.forceFields()) field->addForce(s, B);
  return B;
}

TEST(PointLoad, ReachesTheControlPointsThroughTheBasisRow) {
  // Q_j = b_j(s) F: the forces sum to F (the basis is a partition of unity) and their moment
  // about the origin is P(s) × F (Σ b_j q_j × F), both to round-off (1e-15 relative to |F|).
  const Vec3 F(0.2, -0.1, 0.05);
  auto scene = threadWithLoad({{"type", "PointLoad"}, {"abscissa", 0.37}, {"force", {F.x(), F.y(), F.z()}}});
  const VecX B = loadForces(*scene, 0.0);
  const CurveBody& curve = *scene->bodies().front()->curve();
  Vec3 sum = Vec3::Zero(), moment = Vec3::Zero();
  for (int j = 0; j < curve.pointCount(); ++j) {
    sum += B.segment<3>(3 * j);
    moment += curve.block(scene->state().q).row(j).transpose().cross(B.segment<3>(3 * j));
  }
  EXPECT_LE((sum - F).norm(), 1e-15 * F.norm() * curve.pointCount());
  EXPECT_LE((moment - curve.position(scene->state().q, 0.37).cross(F)).norm(), 1e-15 * F.norm());
  // The energy is the force's work: −F · P(s).
  EXPECT_DOUBLE_EQ(scene->forceFields().front()->potentialEnergy(scene->state()),
                   -F.dot(curve.position(scene->state().q, 0.37)));
}

TEST(PointLoad, FollowsItsPathLinearlyAndHoldsItsEnds) {
  auto scene = threadWithLoad({{"type", "PointLoad"},
                               {"abscissa", 1.0},
                               {"path", {{{"time", 0.1}, {"force", {0, 0, 0}}}, {{"time", 0.3}, {"force", {0, 0, -2}}}}}});
  const auto& load = dynamic_cast<const mechanics::PointLoad&>(*scene->forceFields().front());
  EXPECT_EQ(load.loadAt(0.0).force, Vec3::Zero());          // before the first keyframe: held
  EXPECT_DOUBLE_EQ(load.loadAt(0.25).force.z(), -1.5);      // three quarters of the way
  EXPECT_DOUBLE_EQ(load.loadAt(9.0).force.z(), -2.0);       // after the last: held
}

void expectRefused(const json& load, const std::string& expected_fragment) {
  try {
    threadWithLoad(load);
    ADD_FAILURE() << "accepted: " << load.dump();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(expected_fragment), std::string::npos) << e.what();
  }
}

TEST(PointLoad, RefusesBadInputNamingThePlace) {
  expectRefused({{"type", "PointLoad"}, {"abscissa", 0.5}}, "force");
  expectRefused({{"type", "PointLoad"}, {"abscissa", 1.5}, {"force", {0, 0, 1}}}, "abscissa");
  expectRefused({{"type", "PointLoad"}, {"abscissa", 0.5}, {"force", {0, 0, 1}}, {"path", json::array()}}, "either");
  expectRefused({{"type", "PointLoad"},
                 {"abscissa", 0.5},
                 {"path", {{{"time", 0.2}, {"force", {0, 0, 1}}}, {{"time", 0.1}, {"force", {0, 0, 1}}}}}},
                "/path/1/time");
  // A spline's control points take no torque.
  expectRefused({{"type", "PointLoad"}, {"abscissa", 0.5}, {"torque", {0, 0, 1}}}, "material frames");
  // RodEndFrame needs a rod.
  expectRefused({{"type", "RodEndFrame"}}, "FramedChain");
}

}  // namespace
}  // namespace filum
