// The contact Newton's steps solved through A's band (AugmentedNewtonSystem) against the dense
// LU of J_SS, on contact problems W = L A⁻¹ Lᵀ built from a random symmetric positive definite
// block band A (a thread's step matrix: 3 × 3 blocks, neighbours within two points) and rows of
// contacts on two to four consecutive points (a spline point against an obstacle), some between
// points 15 apart on the thread (+w on one side, −w on the other: self-contacts), μ = 0.3, and an
// equality row (a fixed point). The augmented system's Schur complement is J_SS exactly, so both
// take the same Newton steps up to round-off: the same iterations, and multipliers that agree to
// the round-off of those steps, ε · cond(W + R) (the condition number checked below 4.5e7), at
// 1e-8. The augmented
// system itself is checked against J_SS directly, with two bodies, one of them with interleaved
// internal groups, contacts between them and sliding pairs; and with a wire inside a catheter,
// whose envelope must grow only linearly with the pair's length.
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>

#include <limits>

#include "filum/constraints/contact_newton.hpp"
#include "support/band_matrix.hpp"

namespace filum::constraints {
namespace {

using test::BandMatrix;
using test::delassus;

/// J_SS + δ I formed densely from the rows' forms and W (every row solved).
MatX newtonJacobian(const std::vector<NewtonRowForm>& forms, const MatX& w, double damping) {
  const int c = static_cast<int>(forms.size());
  MatX jss = MatX::Zero(c, c);
  for (int r = 0; r < c; ++r) {
    for (int j = 0; j < forms[r].nb; ++j) jss.row(r) += forms[r].b[j] * w.row(forms[r].bk[j]);
    for (int j = 0; j < forms[r].nc; ++j) jss(r, forms[r].ck[j]) += forms[r].c[j];
    jss(r, r) += damping;
  }
  return jss;
}

TEST(StructuredNewtonStep, TheAugmentedSystemsSolutionIsJssInverseTimesTheRightHandSide) {
  // Two bodies — a rod (30 points interleaved with 30 frame triples, neighbours within 3 groups)
  // and a thread (25 points, within 2) — with contacts on each, one between them, and a fixed
  // point; every row solved: tied rows (J_r = ρ W_r + ρ R e_r) and, on every other contact, a
  // sliding pair (J_t = Σ b W over n, t1, t2 and unit terms on them, random as the Alart–Curnier
  // derivative makes them). The augmented system's Δ against the dense J_SS + δ I solved by
  // Eigen's LU: both backward stable, so they agree to ε · cond(J_SS) (printed; asserted below
  // 1e6) times a factor 1e3 for the size of the systems.
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  const BandMatrix a({{30, 3, true}, {25, 2, false}}, rng);
  ConstraintProblem problem;
  problem.bodies = {BodyBlock{0, 30}, BodyBlock{30, 25}};
  problem.dof_points = 55;
  std::vector<int> point_body(55, 0);
  for (int p = 30; p < 55; ++p) point_body[p] = 1;
  ConstraintRows rows;
  rows.clear();
  rows.beginAnchor();
  rows.addAnchorPoint(40, 1.0);
  for (int axis = 0; axis < 3; ++axis) rows.addAnchoredRow(Vec3::Unit(axis), 0.0);
  auto contact = [&](std::initializer_list<std::pair<int, double>> anchor) {
    rows.beginAnchor();
    for (const auto& [p, w] : anchor) rows.addAnchorPoint(p, w);
    Vec3 n(normal(rng), normal(rng), normal(rng));
    n.normalize();
    const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    rows.addContactRows(n, 0.0, 0.3, t1, 0.0, t2, 0.0);
  };
  for (int k = 0; k < 9; ++k) contact({{2 + 3 * k, 0.5}, {3 + 3 * k, 0.5}});          // the rod on an obstacle
  for (int k = 0; k < 7; ++k) contact({{31 + 3 * k, 0.3}, {32 + 3 * k, 0.7}});        // the thread on an obstacle
  contact({{12, 0.5}, {13, 0.5}, {45, -0.4}, {46, -0.6}});                             // the rod against the thread
  contact({{5, 1.0}, {25, -1.0}});                                                      // the rod against itself
  const int c = rows.rows();
  const MatX w = delassus(rows, a, problem);
  // Forms: every row solved.
  std::vector<NewtonRowForm> forms(c);
  std::vector<int> solved(c), position(c);
  for (int r = 0; r < c; ++r) solved[r] = position[r] = r;
  const double compliance = 1e-6;
  int sliding = 0;
  for (int r = 0; r < c; ++r) {
    const double rho = 1.0 / w(r, r);
    const bool friction = rows.kind(r) == ConstraintRows::Kind::kFriction;
    const int n = friction ? (rows.kind(r - 1) == ConstraintRows::Kind::kNormal ? r - 1 : r - 2) : r;
    if (friction && (n / 3) % 2 == 1) {  // a sliding pair: W terms on n, t1, t2 and unit terms
      const int t1 = n + 1, t2 = n + 2;
      for (int k : {n, t1, t2}) forms[r].addW(k, 0.5 * normal(rng) / w(k, k));
      forms[r].addUnit(r, 1.0 + 0.2 * normal(rng));
      forms[r].addUnit(r == t1 ? t2 : t1, 0.2 * normal(rng));
      forms[r].addUnit(n, 0.2 * normal(rng));
      ++sliding;
      continue;
    }
    forms[r].addW(r, rho);
    forms[r].addUnit(r, rho * compliance * w(r, r));
  }
  ASSERT_GT(sliding, 0);
  const double damping = 1e-6;
  const MatX jss = newtonJacobian(forms, w, damping);
  VecX rhs(c);
  for (int r = 0; r < c; ++r) rhs[r] = normal(rng);
  const VecX reference = jss.partialPivLu().solve(rhs);
  AugmentedNewtonSystem system;
  ASSERT_TRUE(system.build(rows, solved, position, forms, damping, a, problem, point_body));
  ASSERT_TRUE(system.factor());
  VecX delta = rhs;
  system.solve(delta);
  const Eigen::JacobiSVD<MatX> svd(jss);
  const double cond = svd.singularValues()(0) / svd.singularValues()(c - 1);
  std::printf("  %d rows, %d sliding, cond(J_SS) %.3g\n", c, sliding, cond);
  ASSERT_LT(cond, 1e6);
  EXPECT_LE((delta - reference).lpNorm<Eigen::Infinity>(),
            1e3 * cond * std::numeric_limits<double>::epsilon() * reference.lpNorm<Eigen::Infinity>());
}

/// A wire inside a catheter: a rod (`segments` + 1 points interleaved with frame triples,
/// neighbours within 3 groups) and a thread (`segments` points, within 2), the thread's point k
/// lying in the rod's segment (k, k + 1): a contact between them there (n, t1, t2), and one of
/// every two pairs sliding. Its augmented system's envelope LU cost (Σ width²) and, when asked,
/// its solution against the dense J_SS + δ I.
struct CoaxialPair {
  double cost = 0.0;
  bool factored = false;
  double error = 0.0, bound = 0.0;  // |Δ − Δ_dense|∞ and ε cond(J_SS) |Δ_dense|∞ · 1e3
};

CoaxialPair coaxialPair(int segments, bool compare) {
  std::mt19937 rng(17);
  std::normal_distribution<double> normal(0.0, 1.0);
  const int rod = segments + 1, thread = segments;
  const BandMatrix a({{rod, 3, true}, {thread, 2, false}}, rng);
  ConstraintProblem problem;
  problem.bodies = {BodyBlock{0, rod}, BodyBlock{rod, thread}};
  problem.dof_points = rod + thread;
  std::vector<int> point_body(rod + thread, 0);
  for (int p = rod; p < rod + thread; ++p) point_body[p] = 1;
  ConstraintRows rows;
  rows.clear();
  for (int k = 0; k < segments; ++k) {
    rows.beginAnchor();
    rows.addAnchorPoint(rod + k, 1.0);
    rows.addAnchorPoint(k, -0.5);
    rows.addAnchorPoint(k + 1, -0.5);
    Vec3 n(normal(rng), normal(rng), normal(rng));
    n.normalize();
    const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    rows.addContactRows(n, 0.0, 0.05, t1, 0.0, t2, 0.0);
  }
  const int c = rows.rows();
  const MatX w = delassus(rows, a, problem);
  std::vector<NewtonRowForm> forms(c);
  std::vector<int> solved(c), position(c);
  for (int r = 0; r < c; ++r) solved[r] = position[r] = r;
  for (int r = 0; r < c; ++r) {
    const int n = r - r % 3;
    if (r % 3 != 0 && (n / 3) % 2 == 1) {  // a sliding pair's friction row
      for (int k : {n, n + 1, n + 2}) forms[r].addW(k, 0.5 * normal(rng) / w(k, k));
      forms[r].addUnit(r, 1.0 + 0.2 * normal(rng));
      forms[r].addUnit(n, 0.2 * normal(rng));
      continue;
    }
    forms[r].addW(r, 1.0 / w(r, r));
    forms[r].addUnit(r, 1e-6);
  }
  const double damping = 1e-6;
  AugmentedNewtonSystem system;
  CoaxialPair out;
  if (!system.build(rows, solved, position, forms, damping, a, problem, point_body)) return out;
  out.cost = system.cost();
  if (!compare) return out;
  const MatX jss = newtonJacobian(forms, w, damping);
  VecX rhs(c);
  for (int r = 0; r < c; ++r) rhs[r] = normal(rng);
  const VecX reference = jss.partialPivLu().solve(rhs);
  if (!system.factor()) return out;
  out.factored = true;
  VecX delta = rhs;
  system.solve(delta);
  const Eigen::JacobiSVD<MatX> svd(jss);
  const double cond = svd.singularValues()(0) / svd.singularValues()(c - 1);
  std::printf("  coaxial pair of %d segments: %d rows, cond(J_SS) %.3g, envelope cost %.0f (dense %.0f)\n", segments,
              c, cond, out.cost, c * double(c) * c / 3.0);
  out.error = (delta - reference).lpNorm<Eigen::Infinity>();
  out.bound = 1e3 * cond * std::numeric_limits<double>::epsilon() * reference.lpNorm<Eigen::Infinity>();
  return out;
}

TEST(StructuredNewtonStep, MergesAWireAndItsCatheterAlongEachOther) {
  // Laid one body after the other, every row between them would reach back across the whole
  // first body: an envelope as wide as the pair, a cost cubic in its length. Merged along each
  // other (augmented_newton_system.hpp), each unit of length (a segment of the rod, its frame, the
  // thread's point and their three rows) has the same envelope whatever the length, so the cost
  // grows by exactly the same integer sum Σ width² per 40 segments added (the structure is
  // periodic; only the values are random, and the ends are alike at every length).
  const CoaxialPair short_pair = coaxialPair(40, true), pair = coaxialPair(80, false), long_pair = coaxialPair(120, false);
  ASSERT_GT(short_pair.cost, 0.0);
  EXPECT_EQ(long_pair.cost - pair.cost, pair.cost - short_pair.cost);
  // And it solves the same system as J_SS: backward stable both, so to ε cond(J_SS), times 1e3 for
  // the systems' size (as above).
  ASSERT_TRUE(short_pair.factored);
  EXPECT_LE(short_pair.error, short_pair.bound);
}

TEST(StructuredNewtonStep, TakesTheDenseLusStepsThroughTheBand) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  const int points = 300;
  int structured_trials = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const BandMatrix a({{points, 2, false}}, rng);
    ConstraintRows rows;
    rows.clear();
    // A fixed point (three equality rows) at point 3.
    rows.beginAnchor();
    rows.addAnchorPoint(3, 1.0);
    for (int axis = 0; axis < 3; ++axis) rows.addAnchoredRow(Vec3::Unit(axis), 0.1 * normal(rng));
    const int contacts = 100 + trial % 5;
    for (int k = 0; k < contacts; ++k) {
      rows.beginAnchor();
      const int first = 5 + static_cast<int>(rng() % (points - 25)), span = 2 + static_cast<int>(rng() % 3);
      for (int p = first; p < first + span && p < points; ++p) rows.addAnchorPoint(p, 1.0 / span);
      if (k % 8 == 7) rows.addAnchorPoint(first + 15, -1.0);  // a self-contact, 15 points on
      Vec3 n(normal(rng), normal(rng), normal(rng));
      n.normalize();
      const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
      rows.addContactRows(n, normal(rng), 0.3, t1, normal(rng), t2, normal(rng));
    }
    const int c = rows.rows();
    // W = L A⁻¹ Lᵀ.
    MatX l = MatX::Zero(c, 3 * points);
    for (int r = 0; r < c; ++r)
      for (int t = rows.begin(r); t < rows.end(r); ++t) l.block<1, 3>(r, 3 * rows.point(t)) += rows.coeff(t).transpose();
    const MatX w = l * a.pointInverse(0) * l.transpose();
    VecX beta(c);
    for (int r = 0; r < c; ++r) beta[r] = rows.rhs(r);
    VecX compliance = VecX::Zero(c);
    for (int r = 0; r < c; ++r)
      if (rows.kind(r) != ConstraintRows::Kind::kEquality) compliance[r] = 1e-6 * w(r, r);
    ConstraintProblem problem;
    problem.bodies.push_back(BodyBlock{0, points});
    problem.dof_points = points;
    problem.state_size = 3 * points;
    const std::vector<int> point_body(points, 0);
    const ContactNewton::Structure structure{&a, &problem, &point_body};

    ContactNewton dense, banded;
    ContactNewton::Settings settings;
    settings.structured = false;
    VecX lambda_dense = VecX::Zero(c), lambda_banded = VecX::Zero(c);
    const auto by_lu = dense.solve(w, beta, compliance, rows, settings, 1e-12, lambda_dense);
    settings.structured = true;
    const auto by_band = banded.solve(w, beta, compliance, rows, settings, 1e-12, lambda_banded, &structure);
    ASSERT_TRUE(by_lu.converged) << trial;
    ASSERT_TRUE(by_band.converged) << trial;
    EXPECT_EQ(by_lu.structured_steps, 0);
    EXPECT_EQ(by_band.iterations, by_lu.iterations) << trial;
    if (by_band.structured_steps > 0) ++structured_trials;
    // Both runs take the same iterates (the same count, asserted above); they differ by the
    // round-off of backward-stable solves of the shifted Newton system (and of W's products, which
    // the banded run takes as L A⁻¹ Lᵀ x: round-off of |W||x|, smaller), whose rows scaled by ρ are
    // a principal block of W + R: relative ε · cond(W + R) per step, Newton's contraction keeping
    // the last step's. 1e-8 holds that for cond(W + R) up to 1e-8/ε = 4.5e7 (these problems:
    // 7e6–1.7e7, redundant contacts made solvable by the compliance).
    const Eigen::JacobiSVD<MatX> svd(w + MatX(compliance.asDiagonal()));
    const double cond = svd.singularValues()(0) / svd.singularValues()(c - 1);
    ASSERT_LE(cond, 1e-8 / std::numeric_limits<double>::epsilon()) << trial;
    EXPECT_LE((lambda_banded - lambda_dense).lpNorm<Eigen::Infinity>(), 1e-8 * lambda_dense.lpNorm<Eigen::Infinity>())
        << trial;
  }
  // The band is taken when cheaper than the dense LU, which depends on how many rows are active
  // (not free) at each step: with about 300 rows on a band of 900 coordinates, in every trial.
  std::printf("  %d of 10 trials solved steps through the band\n", structured_trials);
  EXPECT_EQ(structured_trials, 10);
}

}  // namespace
}  // namespace filum::constraints
