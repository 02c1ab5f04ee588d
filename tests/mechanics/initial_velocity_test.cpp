// Initial velocities of a DynamicSpline ("velocities" in a scene): the state starts with them,
// a free body keeps its momentum, and a wrong list is refused with its place.
#include <gtest/gtest.h>

#include <algorithm>

#include "filum/core/scene_error.hpp"
#include "support/mechanics_scenes.hpp"

namespace filum {
namespace {

nlohmann::json withVelocities(const test::ThreadSpec& spec, const nlohmann::json& velocities) {
  nlohmann::json scene = test::threadWith(spec, nlohmann::json::array());
  scene["nodes"][0]["components"][0]["velocities"] = velocities;
  return scene;
}

TEST(InitialVelocity, AFreeThreadMovingAsOneTranslatesRigidly) {
  // No force but gravity (switched off) and no constraint: M A = 0, so every control point keeps
  // v = u and moves by u t. Symplectic Euler adds v dt each step: after k steps q = q0 + k dt u,
  // a sum of k equal terms, so the error is k rounding errors of size ε |q| (1e-13 for k = 100,
  // |q| <= 0.2 m): 1e-12 m leaves room for the accumulation.
  test::ThreadSpec spec;
  spec.gravity.setZero();
  spec.integrator = {{"type", "SymplecticEuler"}};
  const Eigen::RowVector3d u(0.3, -2.0, 10.0);
  nlohmann::json list = nlohmann::json::array();
  for (int i = 0; i < spec.control_points; ++i) list.push_back({u.x(), u.y(), u.z()});
  static const Factory factory = app::makeFactory();
  auto scene = loadScene(withVelocities(spec, list), "moving thread", factory);
  const Points q0 = ConstPointsMap(scene->state().q.data(), spec.control_points, 3);
  for (int i = 0; i < spec.control_points; ++i)
    EXPECT_EQ(ConstPointsMap(scene->state().v.data(), spec.control_points, 3).row(i), u) << "control point " << i;
  for (int k = 0; k < 100; ++k) ASSERT_TRUE(scene->step().ok);
  const double t = scene->state().time;
  const ConstPointsMap q(scene->state().q.data(), spec.control_points, 3);
  for (int i = 0; i < spec.control_points; ++i) {
    EXPECT_LE((q.row(i) - q0.row(i) - t * u).norm(), 1e-12) << "control point " << i;
    EXPECT_LE((ConstPointsMap(scene->state().v.data(), spec.control_points, 3).row(i) - u).norm(), 1e-12);
  }
}

TEST(InitialVelocity, EndsYankedApartKeepTheThreadsMomentum) {
  // The two end control points moving apart at 10 m/s (a trainee yanking a 3-0 suture), with
  // stretching and bending and no gravity: internal forces sum to zero (translation invariance,
  // Σ_i f_i = 0), so symplectic Euler keeps the momentum p = Σ_ij M_ij v_j = 1ᵀ M v exactly up to
  // round-off: each step adds dt Σ_i f_i, whose terms of size |f| ~ E A ε_strain cancel to
  // ~n ε |f| dt. Momentum starts at 0 (opposite ends, same mass row sums): after 100 steps
  // |p| <= 100 n ε max|M v| with margin, 1e-12 of the initial end momentum |M v| ~ 1e-5 kg m/s.
  test::ThreadSpec spec;
  spec.gravity.setZero();
  spec.integrator = {{"type", "SymplecticEuler"}};
  spec.dt = 1e-7;  // below the stiff stretching's stability limit of explicit steps
  nlohmann::json scene_json = test::threadWith(spec, nlohmann::json::array(
      {{{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}},
       {{"type", "ParametricBending"}, {"youngs_modulus", 2e9}}}));
  nlohmann::json list = nlohmann::json::array();
  for (int i = 0; i < spec.control_points; ++i) list.push_back({0.0, 0.0, 0.0});
  list[0] = {-10.0, 0.0, 0.0};
  list[spec.control_points - 1] = {10.0, 0.0, 0.0};
  scene_json["nodes"][0]["components"][0]["velocities"] = list;
  static const Factory factory = app::makeFactory();
  auto scene = loadScene(scene_json, "yanked thread", factory);
  const MechanicalState& body = *scene->bodies().front();
  auto momentum = [&] {
    Points Mv(spec.control_points, 3);
    body.multiplyMass(body.block(scene->state().v), Mv);
    return Eigen::Vector3d(Mv.colwise().sum().transpose());
  };
  Points Mv0(spec.control_points, 3);
  body.multiplyMass(body.block(scene->state().v), Mv0);
  const double scale = Mv0.rowwise().norm().maxCoeff();
  ASSERT_GT(scale, 0.0);
  EXPECT_LE(momentum().norm(), 1e-12 * scale);  // symmetric rows of M: the opposite ends cancel
  // The ends first move apart, then the stiff thread pulls them back (its fastest mode has a
  // period of about 1e-5 s, the length of the run): the largest spread exceeds the initial one.
  auto spread = [&] { return scene->state().q[3 * (spec.control_points - 1)] - scene->state().q[0]; };
  const double spread0 = spread();
  double largest = spread0;
  for (int k = 0; k < 100; ++k) {
    ASSERT_TRUE(scene->step().ok);
    largest = std::max(largest, spread());
  }
  EXPECT_GT(largest, spread0);  // yanked apart
  EXPECT_LE(momentum().norm(), 1e-12 * scale);
}

TEST(InitialVelocity, AListOfTheWrongLengthIsRefusedWithItsPlace) {
  test::ThreadSpec spec;
  static const Factory factory = app::makeFactory();
  try {
    loadScene(withVelocities(spec, {{0.0, 0.0, 1.0}}), "short list", factory);
    FAIL() << "a list of 1 velocity for 8 control points was accepted";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("/nodes/0/components/0/velocities"), std::string::npos) << message;
    EXPECT_NE(message.find("8"), std::string::npos) << message;
  }
  nlohmann::json list = nlohmann::json::array();
  for (int i = 0; i < spec.control_points; ++i) list.push_back({0.0, 2e6, 0.0});
  EXPECT_THROW(loadScene(withVelocities(spec, list), "too fast", factory), SceneError);
}

}  // namespace
}  // namespace filum
