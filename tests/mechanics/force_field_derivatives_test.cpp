// Every force field against finite differences (tests/support/force_field_check.hpp): the force
// is −∂E/∂q, and the analytic Jacobians K = ∂Q/∂q and D = ∂Q/∂q̇ that the implicit integrators
// use are the derivatives of the force. Each field acts alone on an 8-control-point thread of
// 10 cm whose control points are moved randomly by up to 1 cm (a curved, stretched and
// compressed state), at rest and with random velocities up to 0.1 m/s.
//
// Tolerance. Step h = 1e-7 m on coordinates of 0.1 m. The forces vary over the segment length
// ℓ ≈ 2 cm, so the truncation error h²/6 |Q'''| is ~ (h/ℓ)² ≈ 3e-11 of the largest entry and the
// round-off ε |Q| / (h |K|) ~ ε ℓ / h ≈ 4e-11 (ε |E| / (h |Q|), the same, for the gradient).
// 1e-7 leaves three orders of magnitude of margin; a missing term of any entry larger than
// 1e-7 of the largest shows.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "support/finite_difference.hpp"
#include "support/force_field_check.hpp"
#include "support/mechanics_scenes.hpp"

namespace filum {
namespace {

using nlohmann::json;

constexpr double kStep = 1e-7;
constexpr double kTolerance = 1e-7;

/// The thread's state with control points moved by up to 1 cm and, if moving, random
/// velocities up to 0.1 m/s.
SceneState perturbed(const Scene& scene, bool moving, unsigned seed) {
  SceneState s = scene.state();
  const int n = scene.dofPointCount();
  const Points dq = test::randomPoints(n, 0.01, seed);
  s.q += Eigen::Map<const VecX>(dq.data(), 3 * n);
  if (moving) {
    const Points v = test::randomPoints(n, 0.1, seed + 1);
    s.v = Eigen::Map<const VecX>(v.data(), 3 * n);
  }
  return s;
}

struct FieldCase {
  std::string label;
  json component;
  bool conservative;  // has a potential: check Q = −∂E/∂q (at rest)
  bool stiffness_when_moving = true;  // false when ∂Q/∂q is documented as omitted for q̇ ≠ 0
  json extra = json::array();         // other components (the fields a RayleighDamping damps)
};

void checkField(const FieldCase& c) {
  json components = c.extra;
  components.push_back(c.component);
  test::ThreadSpec spec;
  auto scene = test::loadThreadWith(spec, components);
  const ForceField& field = *scene->forceFields().back();
  ASSERT_EQ(field.typeName(), c.component["type"].get<std::string>());
  ASSERT_TRUE(field.hasJacobian());

  test::ForceFieldCheck check;
  check.h = kStep;
  check.tolerance = kTolerance;
  for (unsigned seed : {1u, 7u}) {
    // At rest: gradient (conservative fields), K and D.
    check.gradient = c.conservative;
    check.stiffness = true;
    const Eigen::Vector3d at_rest = test::expectForceFieldConsistent(field, perturbed(*scene, false, seed), check);
    // Moving: K (unless documented as omitted) and D.
    check.gradient = false;
    check.stiffness = c.stiffness_when_moving;
    const Eigen::Vector3d moving = test::expectForceFieldConsistent(field, perturbed(*scene, true, seed), check);
    std::cout << "  " << c.label << " (seed " << seed << "): relative errors gradient " << at_rest[0] << ", K "
              << std::max(at_rest[1], moving[1]) << ", D " << std::max(at_rest[2], moving[2]) << '\n';
  }
}

TEST(ForceFieldDerivatives, GreenLagrangeStretching) {
  checkField({"GreenLagrangeStretching", {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}}, true});
  checkField({"GreenLagrangeStretching with rest length",
              {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}, {"rest_length", 0.09}, {"quadrature_nodes", 3}},
              true});
}

TEST(ForceFieldDerivatives, GlobalStretching) {
  checkField({"GlobalStretching", {{"type", "GlobalStretching"}, {"youngs_modulus", 2e9}, {"rest_length", 0.11}}, true});
}

TEST(ForceFieldDerivatives, ParametricBending) {
  checkField({"ParametricBending", {{"type", "ParametricBending"}, {"youngs_modulus", 2e9}}, true});
}

TEST(ForceFieldDerivatives, CurvatureBending) {
  checkField({"CurvatureBending", {{"type", "CurvatureBending"}, {"youngs_modulus", 2e9}}, true});
}

TEST(ForceFieldDerivatives, SpringForceFieldWithDashpots) {
  // At rest the dashpots exert nothing: the force is −∂E/∂q. Moving, K includes the dashpot's
  // rotation term c u Δvᵀ P / l and D = c u uᵀ.
  checkField({"SpringForceField",
              {{"type", "SpringForceField"}, {"stretch_stiffness", 10.0}, {"bend_stiffness", 0.5}, {"damping", 0.2}},
              true});
}

TEST(ForceFieldDerivatives, ViscousDamping) {
  checkField({"ViscousDamping", {{"type", "ViscousDamping"}, {"coefficient", 3.0}}, false});
}

TEST(ForceFieldDerivatives, RayleighDamping) {
  // D = β K(q); ∂Q/∂q = β ∂(K(q) q̇)/∂q is exact over fields with a StiffnessDerivative
  // (Green-Lagrange stretching, quadratic bending): checked moving too.
  FieldCase exact{"RayleighDamping over stretching and quadratic bending",
                  {{"type", "RayleighDamping"}, {"stiffness_coefficient", 1e-3}}, false};
  exact.extra = json::array({{{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}},
                             {{"type", "ParametricBending"}, {"youngs_modulus", 2e9}}});
  checkField(exact);
  // Over the exact curvature bending, whose third derivatives are not provided, that part of
  // ∂Q/∂q is omitted by design (rayleigh_damping.hpp): K checked at rest only, where it vanishes.
  FieldCase partial{"RayleighDamping over curvature bending",
                    {{"type", "RayleighDamping"}, {"stiffness_coefficient", 1e-3}}, false, false};
  partial.extra = json::array({{{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}},
                               {{"type", "CurvatureBending"}, {"youngs_modulus", 2e9}}});
  checkField(partial);
  // Lagged over a step ("stiffness_update": "per_step"): K is the one of the first state
  // evaluated at this time and stays fixed for the others, so Q = β K q̇ is linear in q̇ with
  // D = β K and ∂Q/∂q = 0 — what its Jacobian says, checked moving too, over curvature bending.
  FieldCase lagged{"RayleighDamping lagged over curvature bending",
                   {{"type", "RayleighDamping"}, {"stiffness_coefficient", 1e-3}, {"stiffness_update", "per_step"}},
                   false};
  lagged.extra = partial.extra;
  checkField(lagged);
}

TEST(ForceFieldDerivatives, RayleighDampingRefusesAnUnknownStiffnessUpdate) {
  try {
    test::loadThreadWith(test::ThreadSpec{}, json::array({{{"type", "RayleighDamping"},
                                                           {"stiffness_coefficient", 1e-3},
                                                           {"stiffness_update", "sometimes"}}}));
    ADD_FAILURE() << "accepted stiffness_update \"sometimes\"";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("stiffness_update"), std::string::npos) << message;
    EXPECT_NE(message.find("\"per_step\""), std::string::npos) << message;
    EXPECT_NE(message.find("sometimes"), std::string::npos) << message;
  }
}

TEST(ForceFieldDerivatives, DefiniteGreenLagrangeJacobianDropsOnlyTheCompressedTransverseTerm) {
  // "jacobian": "definite" replaces c ε by max(c ε, 0) in K: the same K where every node is
  // stretched, a negative semi-definite K where the thread is compressed (the exact K then has
  // positive eigenvalues: the buckling directions that make M − h²K indefinite), the same force.
  const json exact = {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}};
  json definite = exact;
  definite["jacobian"] = "definite";
  auto a = test::loadThreadWith(test::ThreadSpec{}, json::array({exact}));
  auto b = test::loadThreadWith(test::ThreadSpec{}, json::array({definite}));
  for (const double scale : {1.01, 0.99}) {  // uniformly stretched, then compressed, by 1 %
    SceneState s = a->state();
    s.q *= scale;
    const MatX Ka = test::fieldJacobian(*a->forceFields().back(), s, 1.0, 0.0);
    const MatX Kb = test::fieldJacobian(*b->forceFields().back(), s, 1.0, 0.0);
    const double size = Ka.cwiseAbs().maxCoeff();
    EXPECT_EQ(test::fieldForce(*a->forceFields().back(), s), test::fieldForce(*b->forceFields().back(), s));
    const Eigen::SelfAdjointEigenSolver<MatX> ea(0.5 * (Ka + Ka.transpose())), eb(0.5 * (Kb + Kb.transpose()));
    std::cout << "  scale " << scale << ": largest eigenvalue of K exact " << ea.eigenvalues().maxCoeff() << ", definite "
              << eb.eigenvalues().maxCoeff() << " (|K| " << size << ")\n";
    if (scale > 1.0) {
      EXPECT_LE((Ka - Kb).cwiseAbs().maxCoeff(), 1e-12 * size);
    } else {
      EXPECT_GT(ea.eigenvalues().maxCoeff(), 1e-6 * size);  // c ε < 0: transverse K > 0
      EXPECT_LE(eb.eigenvalues().maxCoeff(), 1e-12 * size);
    }
  }
}

TEST(ForceFieldDerivatives, ConservativeStiffnessesAreSymmetric) {
  // K = −∇²E is symmetric for every energy (to round-off of summing the same products in
  // two orders: 1e-12 of the largest entry).
  for (const char* type : {"GreenLagrangeStretching", "GlobalStretching", "ParametricBending", "CurvatureBending"}) {
    auto scene = test::loadThreadWith(test::ThreadSpec{}, json::array({{{"type", type}, {"youngs_modulus", 2e9}}}));
    const MatX K = test::fieldJacobian(*scene->forceFields().back(), perturbed(*scene, false, 3), 1.0, 0.0);
    EXPECT_LE((K - K.transpose()).cwiseAbs().maxCoeff(), 1e-12 * K.cwiseAbs().maxCoeff()) << type;
  }
}

TEST(ForceFieldDerivatives, KeptHessiansFollowThePositions) {
  // GreenLagrangeStretching and CurvatureBending keep ∇²E for the positions last asked
  // (SupportHessianCache). Asked at s1, then s2, then s1 again, and with another k factor, each
  // answer is the one a fresh field gives at that state: bit for bit, since the same operations
  // run in the same order (a stale replay would differ by the change of K, ~1e-2 relative here).
  for (const char* type : {"GreenLagrangeStretching", "CurvatureBending"}) {
    const json field_json = json::array({{{"type", type}, {"youngs_modulus", 2e9}}});
    auto kept = test::loadThreadWith(test::ThreadSpec{}, field_json);
    const ForceField& field = *kept->forceFields().back();
    const SceneState s1 = perturbed(*kept, false, 11), s2 = perturbed(*kept, false, 12);
    const auto fresh = [&](const SceneState& s, double k_factor) {
      auto scene = test::loadThreadWith(test::ThreadSpec{}, field_json);
      return test::fieldJacobian(*scene->forceFields().back(), s, k_factor, 0.0);
    };
    const MatX K1 = fresh(s1, 1.0), K2 = fresh(s2, 1.0);
    ASSERT_GT((K1 - K2).cwiseAbs().maxCoeff(), 1e-3 * K1.cwiseAbs().maxCoeff()) << type << ": the states must differ";
    EXPECT_EQ(test::fieldJacobian(field, s1, 1.0, 0.0), K1) << type;
    EXPECT_EQ(test::fieldJacobian(field, s1, 1.0, 0.0), K1) << type << " replayed";
    EXPECT_EQ(test::fieldJacobian(field, s2, 1.0, 0.0), K2) << type << " after the positions changed";
    EXPECT_EQ(test::fieldJacobian(field, s1, -2.5, 0.0), fresh(s1, -2.5)) << type << " back, another factor";
  }
}

TEST(ForceFieldDerivatives, EnergiesVanishAtRestAndUnderRigidMotions) {
  // Straight rest shape: every elastic energy is zero at the initial state and after a rigid
  // rotation + translation (its Gauss quadrature reproduces |P'| exactly only up to round-off:
  // 1e-12 J is ~1e-9 of the energy of a 1 % stretch).
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (const char* type : {"GreenLagrangeStretching", "GlobalStretching", "ParametricBending", "CurvatureBending"}) {
    auto scene = test::loadThreadWith(test::ThreadSpec{}, json::array({{{"type", type}, {"youngs_modulus", 2e9}}}));
    const ForceField& field = *scene->forceFields().back();
    SceneState s = scene->state();
    EXPECT_LE(std::abs(field.potentialEnergy(s)), 1e-12) << type;
    for (int i = 0; i < scene->dofPointCount(); ++i) s.q.segment<3>(3 * i) = R * s.q.segment<3>(3 * i) + Vec3(0.3, -1, 2);
    EXPECT_LE(std::abs(field.potentialEnergy(s)), 1e-12) << type << " after a rigid motion";
    EXPECT_LE(test::fieldForce(field, s).cwiseAbs().maxCoeff(), 1e-6) << type << " after a rigid motion";
  }
}

}  // namespace
}  // namespace filum
