// Every constraint's rows against finite differences of its violation (paper §4: the rows of
// L are the Jacobian ∂g/∂q; their right-hand side carries the velocity-product terms of g̈).
//
// 1. Jacobian: L ≈ ∂g/∂q by central differences. Every g here is linear in q at fixed s (the
//    curve is linear in its control points, eq. 1), so the difference quotient has no
//    truncation error; round-off is ε |g| / h with h = 1e-6 m and |g| <= 0.1 m: ~1e-11, far
//    below the tolerance 1e-8 (1 + max |L|) (|L| reaches ~n² for the curvature rows).
//    For the sliding point, whose violation is the whole gap g(q, s) = P(s) − X (3 entries)
//    while its 2 rows are Nᵀ ∂g/∂q, the test checks Nᵀ (∂g/∂q)_FD = L and Nᵀ (∂g/∂s)_FD = 0:
//    the multiplier λ = N μ satisfies the sliding equation (∂g/∂s)ᵀλ = 0 of [Lenoir talk 2008].
// 2. Acceleration level, without stabilization (ω = 0): along q(τ) = q + τ v + ½ τ² A (and
//    s(τ) = s + τ ṡ + ½ τ² s̈), g̈(0) must equal L A − E. Central second difference with
//    h = 2e-4 s: g(τ) is a quadratic in τ for the linear constraints (exact up to round-off
//    4 ε |g| / h² ≈ 1e-9 for |g| ≲ 0.01 m), and for the sliding point a smooth function of s(τ)
//    with truncation h² |g''''| / 12: measured 2.6e-4 at h = 1e-3 in the worst case (a hole on
//    another moving thread), so |g''''| ≈ 3e3 and ~1e-5 at h = 2e-4. Tolerance 1e-6 (1 + |g̈|)
//    for the linear ones, 1e-4 (1 + |g̈|) for the sliding point. Its direct relation is checked
//    the same way: with s̈ from extraAcceleration, the tangential part of g̈ vanishes.
#include <gtest/gtest.h>

#include <random>

#include "filum/constraints/sliding_point_constraint.hpp"
#include "filum/core/scene.hpp"
#include "support/constraint_scenes.hpp"

namespace filum {
namespace {

using nlohmann::json;
using test::ConstraintThread;

struct Case {
  std::string name;
  std::vector<ConstraintThread> threads;
};

/// A second thread 2 cm above the first, for attachments and junctions.
ConstraintThread upperThread(int control_points = 7) {
  ConstraintThread t;
  t.name = "other";
  t.control_points = control_points;
  t.length = 0.06;
  t.origin = {0.1, 0.0, 0.02};
  return t;
}

std::vector<Case> cases() {
  std::vector<Case> out;
  auto single = [&](const std::string& name, json constraint) {
    ConstraintThread t;
    t.constraints.push_back(std::move(constraint));
    t.constraints.back()["stabilization"] = 0.0;
    out.push_back({name, {t}});
  };
  auto pair = [&](const std::string& name, json constraint) {
    ConstraintThread t;
    t.constraints.push_back(std::move(constraint));
    t.constraints.back()["stabilization"] = 0.0;
    out.push_back({name, {t, upperThread()}});
  };
  const json smooth_path = {{{"time", 0.0}, {"position", {0.03, 0.0, 0.0}}},
                            {{"time", 1.0}, {"position", {0.04, 0.01, 0.02}}},
                            {{"time", 2.0}, {"position", {0.05, 0.0, 0.01}}}};
  single("fixed point", {{"type", "FixedPointConstraint"}, {"abscissa", 0.37}});
  single("fixed point, smooth scripted target",
         {{"type", "FixedPointConstraint"}, {"abscissa", 0.3}, {"interpolation", "smooth"}, {"path", smooth_path}});
  pair("fixed point attached to another thread",
       {{"type", "FixedPointConstraint"}, {"abscissa", 1.0}, {"target", {{"object", "other"}, {"abscissa", 0.2}}}});
  single("point on axis", {{"type", "PointOnAxisConstraint"}, {"abscissa", 0.5}, {"axis", {1.0, 1.0, 0.0}}});
  pair("point on axis through an attached point", {{"type", "PointOnAxisConstraint"},
                                                   {"abscissa", 0.8},
                                                   {"axis", {0.0, 0.3, 1.0}},
                                                   {"target", {{"object", "other"}, {"abscissa", 0.5}}}});
  single("point on plane", {{"type", "PointOnPlaneConstraint"}, {"abscissa", 0.9}, {"normal", {0.0, 1.0, 1.0}}});
  single("clamp", {{"type", "ClampConstraint"}, {"abscissa", 0.2}});
  single("clamp on a scripted target, given direction", {{"type", "ClampConstraint"},
                                                         {"abscissa", 0.3},
                                                         {"direction", {1.0, 0.2, 0.0}},
                                                         {"interpolation", "smooth"},
                                                         {"path", smooth_path}});
  single("sliding point", {{"type", "SlidingPointConstraint"}, {"abscissa", 0.45}, {"friction", 1e-4}});
  single("sliding point through a scripted hole", {{"type", "SlidingPointConstraint"},
                                                   {"abscissa", 0.3},
                                                   {"interpolation", "smooth"},
                                                   {"path", smooth_path}});
  pair("sliding point through a hole on another thread",
       {{"type", "SlidingPointConstraint"}, {"abscissa", 0.6}, {"target", {{"object", "other"}, {"abscissa", 0.4}}}});
  for (int k : {0, 1, 2})
    pair("junction C" + std::to_string(k),
         {{"type", "SplineJunctionConstraint"}, {"other", "other"}, {"continuity", k}});
  single("junction C2 of a thread with itself (a loop)",
         {{"type", "SplineJunctionConstraint"}, {"other", "thread"}, {"continuity", 2}});
  return out;
}

/// A state away from the initial one: every DOF perturbed, random velocities (and a random
/// abscissa rate), at t = 0.4 s (inside a segment of the scripted paths).
SceneState perturbedState(const Scene& scene, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SceneState s = scene.state();
  s.time = 0.4;
  const int n3 = 3 * scene.dofPointCount();
  for (int i = 0; i < n3; ++i) {
    s.q[i] += 0.005 * u(rng);
    s.v[i] = 0.1 * u(rng);
  }
  for (int i = n3; i < s.q.size(); ++i) {
    s.q[i] += 0.05 * u(rng);
    s.v[i] = 0.5 * u(rng);
  }
  return s;
}

MatX denseRows(const ConstraintRows& rows, int size) {
  MatX L = MatX::Zero(rows.rows(), size);
  for (int r = 0; r < rows.rows(); ++r)
    for (int t = rows.begin(r); t < rows.end(r); ++t) L.block<1, 3>(r, 3 * rows.point(t)) += rows.coeff(t).transpose();
  return L;
}

VecX violationOf(const Constraint& c, const SceneState& s) {
  VecX g(c.violationCount());
  c.violation(s, g, 0);
  return g;
}

/// The unit directions of the rows (one factor each for the constraints of this library).
MatX rowDirections(const ConstraintRows& rows) {
  MatX N(3, rows.rows());
  for (int r = 0; r < rows.rows(); ++r) {
    EXPECT_EQ(rows.factorEnd(r) - rows.factorBegin(r), 1);
    N.col(r) = rows.factorDirection(rows.factorBegin(r));
  }
  return N;
}

TEST(ConstraintJacobian, RowsAreTheJacobianOfTheViolation) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    auto scene = test::loadConstraintScene(test::constraintScene(c.threads));
    ASSERT_EQ(scene->constraints().size(), 1u);
    const Constraint& constraint = *scene->constraints().front();
    const SceneState s = perturbedState(*scene, 7);
    const int n3 = 3 * scene->dofPointCount();

    ConstraintRows rows;
    rows.clear();
    constraint.buildRows(s, rows);
    ASSERT_EQ(rows.rows(), constraint.rowCount());
    const MatX L = denseRows(rows, n3);

    const double h = 1e-6;
    MatX J(constraint.violationCount(), n3);
    for (int i = 0; i < n3; ++i) {
      SceneState plus = s, minus = s;
      plus.q[i] += h;
      minus.q[i] -= h;
      J.col(i) = (violationOf(constraint, plus) - violationOf(constraint, minus)) / (2 * h);
    }
    const double tolerance = 1e-8 * (1.0 + L.cwiseAbs().maxCoeff());
    if (constraint.extraDofCount() == 0) {
      EXPECT_LE((J - L).cwiseAbs().maxCoeff(), tolerance);
      continue;
    }
    // Sliding point: rows = Nᵀ ∂g/∂q, and Nᵀ ∂g/∂s = 0.
    const MatX N = rowDirections(rows);
    EXPECT_LE((N.transpose() * J - L).cwiseAbs().maxCoeff(), tolerance);
    SceneState plus = s, minus = s;
    plus.q[constraint.extraIndex()] += h;
    minus.q[constraint.extraIndex()] -= h;
    const VecX dgds = (violationOf(constraint, plus) - violationOf(constraint, minus)) / (2 * h);
    EXPECT_GT(dgds.norm(), 1e-3) << "∂g/∂s = P'(s) should be the thread's tangent";
    EXPECT_LE((N.transpose() * dgds).cwiseAbs().maxCoeff(), 1e-8 * dgds.norm());
  }
}

TEST(ConstraintJacobian, RightHandSideHoldsTheVelocityTermsOfTheSecondDerivative) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    auto scene = test::loadConstraintScene(test::constraintScene(c.threads));
    const Constraint& constraint = *scene->constraints().front();
    const SceneState s = perturbedState(*scene, 11);
    const int size = static_cast<int>(s.q.size());
    const int n3 = 3 * scene->dofPointCount();

    // Arbitrary accelerations of every DOF.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    VecX a(size);
    for (int i = 0; i < size; ++i) a[i] = (i < n3 ? 10.0 : 2.0) * u(rng);
    if (constraint.extraDofCount() > 0) constraint.extraAcceleration(s, a);  // the direct relation

    ConstraintRows rows;
    rows.clear();
    constraint.buildRows(s, rows);
    VecX expected(rows.rows());
    for (int r = 0; r < rows.rows(); ++r) expected[r] = rows.dot(r, a) - rows.rhs(r);

    const double h = 2e-4;
    auto at = [&](double tau) {
      SceneState x = s;
      x.time = s.time + tau;
      x.q = s.q + tau * s.v + 0.5 * tau * tau * a;
      x.v = s.v + tau * a;
      return violationOf(constraint, x);
    };
    const VecX gdd = (at(h) - 2.0 * at(0.0) + at(-h)) / (h * h);
    if (constraint.extraDofCount() == 0) {
      EXPECT_LE((gdd - expected).cwiseAbs().maxCoeff(), 1e-6 * (1.0 + gdd.norm()));
      continue;
    }
    const MatX N = rowDirections(rows);
    EXPECT_LE((N.transpose() * gdd - expected).cwiseAbs().maxCoeff(), 1e-4 * (1.0 + gdd.norm()));
    // Tangential part: zero with s̈ from the direct relation (ω = 0: g̈ = 0 along the thread).
    const Vec3 normal_part = N * (N.transpose() * gdd);
    EXPECT_LE((gdd - normal_part).norm(), 1e-4 * (1.0 + gdd.norm()));
  }
}

}  // namespace
}  // namespace filum
