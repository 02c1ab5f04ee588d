// The multiplier solver (paper §4): its shortcuts (scalar anchor solves, reuse of M⁻¹ w between
// calls, sparse factorization with entries below round-off dropped) against the plain
// computation, and the claims lagrange_multiplier_solver.hpp makes about the sparsity of W.
// Speed is measured in apps/bench/bench_constraints.cpp, never asserted here.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "filum/constraints/lagrange_multiplier_solver.hpp"
#include "filum/core/scene.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "support/constraint_scenes.hpp"

namespace filum {
namespace {

using nlohmann::json;
using test::ConstraintThread;

/// A long thread (1 cm between control points) held by `groups` triples {fixed point, point on
/// axis, point on plane} spread evenly along it (6 rows per group).
ConstraintThread longThread(int control_points, int groups) {
  ConstraintThread t;
  t.control_points = control_points;
  t.length = 0.01 * (control_points - 3);
  t.mass = 2.86e-5 * t.length;
  for (int k = 0; k < groups; ++k) {
    const double s = (k + 0.5) / groups;
    const double ds = 0.25 / groups;
    t.constraints.push_back({{"type", "FixedPointConstraint"}, {"abscissa", s}});
    t.constraints.push_back({{"type", "PointOnAxisConstraint"}, {"abscissa", s + ds}, {"axis", {1, 0, 0}}});
    t.constraints.push_back({{"type", "PointOnPlaneConstraint"}, {"abscissa", s + 2 * ds}, {"normal", {0, 0, 1}}});
  }
  return t;
}

json withSolver(json document, json solver) {
  solver["type"] = "LagrangeMultiplierSolver";
  document["constraint_solver"] = solver;
  return document;
}

const constraints::LagrangeMultiplierSolver& solverOf(const Scene& scene) {
  return dynamic_cast<const constraints::LagrangeMultiplierSolver&>(*scene.constraintSolver());
}

/// The scene's state after `steps` steps, perturbed so that no constraint is satisfied.
SceneState movedState(Scene& scene, int steps) {
  for (int k = 0; k < steps; ++k) EXPECT_TRUE(scene.step().ok);
  SceneState s = scene.state();
  for (int i = 0; i < s.q.size(); ++i) s.q[i] += 1e-4 * std::sin(1.3 * i);
  return s;
}

TEST(LagrangeMultiplierSolver, InverseMassDecaysGeometricallyAsTheHeaderSays) {
  // (M⁻¹)_{j,j+k} of the uniform cubic B-spline mass matrix falls like ρ^k, ρ = 0.53528...
  // (the root of modulus < 1 of the degree-7 Euler–Frobenius polynomial), alternating in sign;
  // after 60 control points it is below 1e-16 of the diagonal: why W is numerically sparse
  // between constraints far apart on a long thread.
  ConstraintThread t = longThread(200, 0);
  auto scene = test::loadConstraintScene(test::constraintScene({t}));
  const MechanicalState& body = *scene->bodies().front();
  Points e = Points::Zero(200, 3);
  e(100, 0) = 1.0;
  body.solveMass(e);
  for (int k = 10; k < 40; ++k) EXPECT_NEAR(e(100 + k + 1, 0) / e(100 + k, 0), -0.5352804307964382, 1e-6) << k;
  EXPECT_LT(std::abs(e(160, 0) / e(100, 0)), 1e-16);
}

TEST(LagrangeMultiplierSolver, SparseFactorizationAgreesWithTheDenseOne) {
  // 400 control points, 40 groups = 240 rows 10 control points apart. Dense LDLᵀ of the whole
  // W against the sparse paths: exact entries (τ = 0) and entries below τ = 1e-14 √(W_rr W_kk)
  // dropped. The dropped part is of the order of W's own rounding, so λ and A agree to
  // ~cond(W)·1e-14 (cond(W) ~ 1e2 here): tolerance 1e-10 relative.
  const json document = test::constraintScene({longThread(400, 40)});
  auto dense = test::loadConstraintScene(withSolver(document, {{"sparse_above", 10000}}));
  const SceneState s = movedState(*dense, 10);
  VecX a_dense, a;
  dense->computeAcceleration(s, a_dense);
  const VecX lambda_dense = solverOf(*dense).multipliers();
  ASSERT_FALSE(solverOf(*dense).statistics().sparse);

  std::vector<json> variants = {{{"sparse_above", 0}, {"sparse_solver", "simplicial_ldlt"}},
                                {{"sparse_above", 0}, {"sparse_solver", "simplicial_ldlt"}, {"drop_tolerance", 0.0}}};
  if (constraints::LagrangeMultiplierSolver::cholmodAvailable())
    variants.push_back({{"sparse_above", 0}, {"sparse_solver", "cholmod"}});
  for (const json& variant : variants) {
    SCOPED_TRACE(variant.dump());
    auto sparse = test::loadConstraintScene(withSolver(document, variant));
    sparse->computeAcceleration(s, a);
    const auto& stats = solverOf(*sparse).statistics();
    ASSERT_TRUE(stats.sparse);
    EXPECT_LE((solverOf(*sparse).multipliers() - lambda_dense).norm(), 1e-10 * lambda_dense.norm());
    EXPECT_LE((a - a_dense).norm(), 1e-10 * a_dense.norm());
    const long lower = static_cast<long>(stats.rows) * (stats.rows + 1) / 2;
    std::cout << "  " << variant.dump() << ": " << stats.nonzeros << " of " << lower << " entries of W kept\n";
    if (variant.value("drop_tolerance", 1e-14) > 0) {
      EXPECT_LT(stats.nonzeros, lower / 4);
    }
  }
}

TEST(LagrangeMultiplierSolver, ReusingColumnsChangesNothing) {
  // M⁻¹ w_a kept from one call to the next for unchanged anchors is the same number as solving
  // again: the runs agree bit for bit, and almost every column is reused.
  ConstraintThread t = longThread(60, 3);
  t.constraints.push_back({{"type", "SlidingPointConstraint"}, {"abscissa", 0.95}});  // moves: solved every call
  const json document = test::constraintScene({t});
  auto with = test::loadConstraintScene(withSolver(document, {{"reuse", true}}));
  auto without = test::loadConstraintScene(withSolver(document, {{"reuse", false}}));
  for (int k = 0; k < 300; ++k) {
    ASSERT_TRUE(with->step().ok);
    ASSERT_TRUE(without->step().ok);
  }
  EXPECT_EQ(with->state().q, without->state().q);
  EXPECT_EQ(with->state().v, without->state().v);
  const auto& stats = solverOf(*with).statistics();
  EXPECT_EQ(stats.solved_columns, 1) << "only the sliding point's anchor moves";
  EXPECT_EQ(stats.reused_columns, stats.columns - 1);
  EXPECT_EQ(solverOf(*without).statistics().reused_columns, 0);
}

/// The mass inverse seen as an operator the solver may not shortcut: not the same on every axis
/// (like an implicit step matrix), or coupling the bodies (a whole-scene solve).
class PlainInverse final : public BlockInverse {
 public:
  PlainInverse(const Scene& scene, bool coupled) : scene_(scene), coupled_(coupled) {}
  void solveBlock(int body, Eigen::Ref<VecX> x) const override { scene_.massInverse().solveBlock(body, x); }
  bool coupled() const override { return coupled_; }
  void solveAll(Eigen::Ref<VecX> x) const override {
    for (std::size_t b = 0; b < scene_.bodies().size(); ++b) {
      const MechanicalState& body = *scene_.bodies()[b];
      scene_.massInverse().solveBlock(static_cast<int>(b), x.segment(3 * body.offset(), 3 * body.pointCount()));
    }
  }

 private:
  const Scene& scene_;
  bool coupled_;
};

TEST(LagrangeMultiplierSolver, GeneralOperatorsGiveTheSameAccelerations) {
  // The per-row 3-column path (implicit steps) and the whole-scene path (coupled bodies)
  // compute the same A as the scalar-anchor path, to round-off (1e-12 relative). Three bodies:
  // a junction and a sliding point through a hole carried by a third thread couple them.
  ConstraintThread a = longThread(20, 1), b, c;
  b.name = "second";
  b.control_points = 9;
  b.origin = {0.17, 0.0, 0.0};
  b.constraints = {json{{"type", "SplineJunctionConstraint"}, {"other", "thread"}, {"abscissa", 0.0},
                        {"other_abscissa", 1.0}, {"continuity", 2}},
                   json{{"type", "ClampConstraint"}, {"abscissa", 1.0}},
                   json{{"type", "SlidingPointConstraint"}, {"abscissa", 0.5},
                        {"target", {{"object", "third"}, {"abscissa", 0.5}}}}};
  c.name = "third";
  c.control_points = 6;
  c.length = 0.06;
  c.origin = {0.19, 0.0, 0.0};
  c.constraints = {json{{"type", "FixedPointConstraint"}, {"abscissa", 0.0}}};
  auto scene = test::loadConstraintScene(test::constraintScene({a, b, c}));
  const SceneState s = movedState(*scene, 50);
  for (const Constraint* constraint : scene->constraints()) ASSERT_TRUE(constraint->active());
  VecX reference;
  scene->computeAcceleration(s, reference);
  const int n3 = 3 * scene->dofPointCount();

  // Tendency accelerations and rows as the scene builds them.
  VecX force, tendency(s.q.size());
  scene->computeForce(s, force);
  tendency.setZero();
  tendency.head(n3) = force.head(n3);  // forces are laid out as v: points first
  for (const MechanicalState* body : scene->bodies()) body->solveMass(body->block(tendency));
  ConstraintRows rows;
  rows.clear();
  for (const Constraint* constraint : scene->constraints()) constraint->buildRows(s, rows);

  for (bool coupled : {false, true}) {
    constraints::LagrangeMultiplierSolver solver;
    VecX acc = tendency;
    solver.solve(scene->constraintProblem(), rows, PlainInverse(*scene, coupled), acc);
    EXPECT_EQ(solver.statistics().columns, rows.rows());
    EXPECT_LE((acc.head(n3) - reference.head(n3)).norm(), 1e-12 * reference.head(n3).norm()) << coupled;
  }
}

TEST(LagrangeMultiplierSolver, MultipliersAreTheHoldingForces) {
  // A thread hanging at rest from its start: M A = B + Lᵀλ with A = 0, so Σ_i (Lᵀλ)_i =
  // −Σ_i Q_i = −m g (Σ_i ∫ b_i = 1): the fixed point's multiplier is the thread's weight
  // pointing up. Damping 20/s for 2 s leaves velocities ~1e-9 m/s: tolerance 1e-6 relative.
  ConstraintThread t;
  t.viscous_damping = 20.0;
  t.constraints = {json{{"type", "FixedPointConstraint"}, {"abscissa", 0.0}}};
  auto scene = test::loadConstraintScene(test::constraintScene({t}));
  for (int k = 0; k < 20000; ++k) ASSERT_TRUE(scene->step().ok);
  const VecX& lambda = solverOf(*scene).multipliers();
  const double weight = 2.86e-6 * 9.81;
  EXPECT_NEAR(lambda[2], weight, 1e-6 * weight);
  EXPECT_NEAR(lambda[0], 0.0, 1e-6 * weight);
  EXPECT_NEAR(lambda[1], 0.0, 1e-6 * weight);
}

TEST(LagrangeMultiplierSolver, WorksUnderAnImplicitIntegrator) {
  // Implicit steps constrain through their own step matrix (BlockInverse not the same on every
  // axis): the per-row path. The constraints hold as with RK4, to the integrator's accuracy.
  const Factory factory = app::makeFactory();
  ASSERT_TRUE(factory.knows("ImplicitEuler"));  // mechanics/ always registers it: no build leaves it out
  std::vector<ConstraintThread> parts(2);
  parts[0].constraints = {json{{"type", "ClampConstraint"}, {"abscissa", 0.0}},
                          json{{"type", "SplineJunctionConstraint"}, {"other", "second"}, {"continuity", 2}}};
  parts[1].name = "second";
  parts[1].origin = {0.1, 0.0, 0.0};
  parts[1].constraints = {json{{"type", "PointOnPlaneConstraint"}, {"abscissa", 1.0}, {"normal", {0, 0, 1}}}};
  // A scene the integrator refused would be a failure of this test, not a reason to skip it.
  const std::unique_ptr<Scene> scene = loadScene(test::constraintScene(parts, 1e-4, "ImplicitEuler"), "implicit", factory);
  const double worst = test::maxViolationOver(*scene, 3000);
  std::cout << "  ImplicitEuler, clamp + C2 junction + plane: violation <= " << worst << " m\n";
  EXPECT_LE(worst, 1e-8);
}

}  // namespace
}  // namespace filum
