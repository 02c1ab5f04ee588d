// The contact Newton with W left unformed (lagrange_multiplier_solver.hpp, step 2: its products
// through A's band, its diagonal from A⁻¹'s blocks within the band by Takahashi's equations, W
// formed only when a dense LU step asks for it) against the same solver with W formed and every
// step by the dense LU ("newton_linear_solve": "dense"), on contact problems through a random
// block band A (test::BandMatrix: a rod's points interleaved with its frames, neighbours within
// two groups) with a fixed point (three equality rows) and contacts on two consecutive points.
//
// Tolerance. Both solve the same problem to a relative residual of τ = 1e-12 (contact_tolerance)
// by Newton steps that differ by round-off — W's products (L A⁻¹ Lᵀ x against W x), W's diagonal
// (from A⁻¹'s band against W's own entries: the scale ρ and the compliance R = 1e-6 W_rr move by
// ε), the step's system (through the band against a dense LU), backward stable each. Two λ whose
// residuals are below τ |λ| (W + R) differ by at most cond(W + R) (2τ + the steps' round-off,
// 1e2 ε) relative: asserted with cond(W + R) computed for each problem.
#include <cstdio>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "filum/constraints/lagrange_multiplier_solver.hpp"
#include "support/row_problem.hpp"

namespace filum::constraints {
namespace {

constexpr double kTolerance = 1e-12;  // τ, the contact solve's relative residual

/// A fixed point at point 3 and `contacts` contacts on points k … k + span (span 1: two
/// consecutive points), their normal rows' β drawn so that about `pressing` of them push (β < 0
/// separates nothing: the row wants a force).
/// With `point_as_contact`, point 3's three rows are a contact (normal along x, friction along y
/// and z) instead of a fixed point: the same points and coefficients, other kinds.
test::RowProblem contactProblem(int points, int contacts, double pressing, std::mt19937& rng, int span = 1,
                                bool point_as_contact = false) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  test::RowProblem out(points);
  ConstraintRows& rows = out.rows;
  rows.beginAnchor();
  rows.addAnchorPoint(3, 1.0);
  double beta[3];
  for (double& b : beta) b = 0.1 * normal(rng);
  if (point_as_contact)
    rows.addContactRows(Vec3::UnitX(), beta[0], 0.3, Vec3::UnitY(), beta[1], Vec3::UnitZ(), beta[2]);
  else
    for (int axis = 0; axis < 3; ++axis) rows.addAnchoredRow(Vec3::Unit(axis), beta[axis]);
  for (int k = 0; k < contacts; ++k) {
    rows.beginAnchor();
    const int first = 5 + static_cast<int>(rng() % (points - 6 - span));
    const double w = uniform(rng);
    if (span == 1) {
      rows.addAnchorPoint(first, 1.0 - w);
      rows.addAnchorPoint(first + 1, w);
    } else {  // weights summing to one over first … first + span
      for (int j = 0; j <= span; ++j) rows.addAnchorPoint(first + j, (j == 0 ? 1.0 - w : w) / (j == 0 ? 1.0 : span));
    }
    Vec3 n(normal(rng), normal(rng), normal(rng));
    n.normalize();
    const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    // β_n > 0: the row asks for a force (an approach to undo); < 0: it separates by itself.
    const double beta_n = uniform(rng) < pressing ? std::abs(normal(rng)) : -std::abs(normal(rng));
    rows.addContactRows(n, beta_n, 0.3, t1, normal(rng), t2, normal(rng));
  }
  return out;
}

/// The problem solved both ways; both converge, and their multipliers agree (see the tolerance above).
struct Comparison {
  test::RowSolve deferred, formed;
};
Comparison solveBothWays(int trial, const test::RowProblem& p, const test::BandMatrix& a) {
  Comparison out{test::solveRows(p, a, true, kTolerance), test::solveRows(p, a, false, kTolerance)};
  std::printf("  trial %d: %d rows, %d and %d Newton iterations (deferred, formed), %d of the first through the band\n",
              trial, p.rows.rows(), out.deferred.stats.newton_iterations, out.formed.stats.newton_iterations,
              out.deferred.stats.structured_steps);
  EXPECT_TRUE(out.deferred.stats.converged) << trial;
  EXPECT_TRUE(out.formed.stats.converged) << trial;
  EXPECT_TRUE(out.deferred.stats.deferred) << trial;
  EXPECT_FALSE(out.formed.stats.deferred) << trial;
  const double cond = test::compliantCondition(p, a);
  const double difference = (out.deferred.lambda - out.formed.lambda).lpNorm<Eigen::Infinity>();
  const double scale = out.formed.lambda.lpNorm<Eigen::Infinity>();
  std::printf("    cond(W + R) %.2g, multipliers %.2g apart relative\n", cond, difference / scale);
  EXPECT_LE(difference, cond * (2.0 * kTolerance + 1e2 * std::numeric_limits<double>::epsilon()) * scale) << trial;
  return out;
}

/// W_rr as the solver took it, against W formed densely (test::delassus) from the same point
/// inverse H: the two sum the same products c_tᵀ H c_u in another order, so they differ by at
/// most γ_n Σ |c_t|ᵀ |H| |c_u| with n the products' count (Higham, "Accuracy and Stability of
/// Numerical Algorithms", 2002, §3.1: γ_n = nε/(1 − nε); two sums, each at most that). One more
/// difference is in the inputs: the solver reads each pair's block below the diagonal, H_ut, and
/// its transpose for H_tu, where the dense W reads H_tu itself; a computed inverse is symmetric
/// only to its round-off, so Σ_{t ≠ u} |c_t|ᵀ |H_tu − H_utᵀ| |c_u|, measured, is added.
void expectDiagonalAsFormed(const test::RowProblem& p, const test::BandMatrix& a, const test::RowSolve& deferred,
                            int trial) {
  const MatX w = test::delassus(p.rows, a, p.problem);
  const MatX inverse = a.pointInverse(0);
  const MatX h = inverse.cwiseAbs();
  for (int r = 0; r < p.rows.rows(); ++r) {
    double magnitude = 0.0, asymmetry = 0.0;
    int products = 0;
    for (int t = p.rows.begin(r); t < p.rows.end(r); ++t)
      for (int u = p.rows.begin(r); u < p.rows.end(r); ++u, products += 9) {
        const int pt = 3 * p.rows.point(t), pu = 3 * p.rows.point(u);
        magnitude += p.rows.coeff(t).cwiseAbs().dot(h.block<3, 3>(pt, pu) * p.rows.coeff(u).cwiseAbs());
        if (pt != pu)
          asymmetry += p.rows.coeff(t).cwiseAbs().dot(
              (inverse.block<3, 3>(pt, pu) - inverse.block<3, 3>(pu, pt).transpose()).cwiseAbs() * p.rows.coeff(u).cwiseAbs());
      }
    const double gamma = products * std::numeric_limits<double>::epsilon();
    EXPECT_LE(std::abs(deferred.diagonal[r] - w(r, r)), 2.0 * gamma / (1.0 - gamma) * magnitude + asymmetry)
        << trial << " row " << r;
  }
}

TEST(DeferredDelassus, SolvesAsTheFormedWWithoutFormingIt) {
  // 150 points (300 groups with the frames) and 80 contacts, 60 % of them pressing: W's c² =
  // 5.9e4 is costlier than two products through the band (2 × 1.6e4), and with ~140 rows active
  // every step goes through the band — W is never formed.
  std::mt19937 rng(21);
  for (int trial = 0; trial < 5; ++trial) {
    const test::BandMatrix a({{150, 2, true}}, rng);
    const test::RowProblem p = contactProblem(150, 80, 0.6, rng);
    const test::RowSolve deferred = solveBothWays(trial, p, a).deferred;
    EXPECT_FALSE(deferred.stats.reassembled) << trial;     // W never formed
    EXPECT_EQ(deferred.stats.solved_columns, 0) << trial;  // nor a column A⁻¹ l_r solved
    EXPECT_EQ(deferred.stats.structured_steps, deferred.stats.newton_iterations) << trial;
  }
}

/// `contacts` contacts between two far parts of one body, as a thread touching itself: the gap
/// P(a) − P(b) between points (a, a + 1) and (b, b + 1), b `apart` to `apart` + 4 points after a.
void addSelfContacts(test::RowProblem& out, int points, int contacts, int apart, std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int k = 0; k < contacts; ++k) {
    out.rows.beginAnchor();
    const int a = 5 + static_cast<int>(rng() % (points - apart - 12));
    const int b = a + apart + static_cast<int>(rng() % 5);
    const double wa = uniform(rng), wb = uniform(rng);
    out.rows.addAnchorPoint(a, 1.0 - wa);
    out.rows.addAnchorPoint(a + 1, wa);
    out.rows.addAnchorPoint(b, -(1.0 - wb));
    out.rows.addAnchorPoint(b + 1, -wb);
    Vec3 n(normal(rng), normal(rng), normal(rng));
    n.normalize();
    const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    out.rows.addContactRows(n, std::abs(normal(rng)), 0.3, t1, normal(rng), t2, normal(rng));
  }
}

TEST(DeferredDelassus, SelfContactsFarAlongTheBodyTakeASolveEachNotAColumnPerRow) {
  // 80 contacts against obstacles and 10 between points 8 to 12 apart (16 groups or more with the
  // frames; the band reaches 2 groups): the far rows' W_rr take one band solve each (l_r · A⁻¹
  // l_r), the others come from A⁻¹'s band as before — no column A⁻¹ l_r per row, W never formed
  // while the steps go through the band — and the solution is the formed W's (the tolerance above:
  // W_rr by another sum order moves ρ and R by ε).
  std::mt19937 rng(29);
  for (int trial = 0; trial < 5; ++trial) {
    const test::BandMatrix a({{150, 2, true}}, rng);
    test::RowProblem p = contactProblem(150, 80, 0.6, rng);
    addSelfContacts(p, 150, 10, 8, rng);
    const test::RowSolve deferred = solveBothWays(trial, p, a).deferred;
    EXPECT_EQ(deferred.stats.far_rows, 3 * 10) << trial;  // a normal and two friction rows each
    EXPECT_FALSE(deferred.stats.reassembled) << trial;
    EXPECT_EQ(deferred.stats.solved_columns, 0) << trial;
    EXPECT_EQ(deferred.stats.structured_steps, deferred.stats.newton_iterations) << trial;
    expectDiagonalAsFormed(p, a, deferred, trial);
  }
}

TEST(DeferredDelassus, RowsOnThreePointsTakeAWiderInverseBandNotASolveEach) {
  // 80 contacts each on three consecutive points (a point of a tube's chord between two sphere
  // centres in two segments of a rod): 4 groups apart with the frames, where the band reaches 2.
  // Takahashi's recurrence widened to 4 block diagonals costs 27 · 2 · 2 multiply-adds a group, a
  // solve per row 45 a group: 240 rows take the wider band (lagrange_multiplier_solver.cpp,
  // inverseBandCovers) — no far row, no column, W never formed — with the formed W's solution.
  std::mt19937 rng(31);
  for (int trial = 0; trial < 5; ++trial) {
    const test::BandMatrix a({{150, 2, true}}, rng);
    const test::RowProblem p = contactProblem(150, 80, 0.6, rng, /*span=*/2);
    const test::RowSolve deferred = solveBothWays(trial, p, a).deferred;
    EXPECT_EQ(deferred.stats.far_rows, 0) << trial;
    EXPECT_EQ(deferred.stats.inverse_range, 4) << trial;
    EXPECT_FALSE(deferred.stats.reassembled) << trial;
    EXPECT_EQ(deferred.stats.solved_columns, 0) << trial;
    EXPECT_EQ(deferred.stats.structured_steps, deferred.stats.newton_iterations) << trial;
    expectDiagonalAsFormed(p, a, deferred, trial);
  }
}

TEST(DeferredDelassus, AFewActiveRowsFormWWhenTheDenseStepAsksForIt) {
  // 10 % of 80 contacts pressing: the solved set stays below the band step's 64 rows, the dense
  // LU asks for W's entries, and W is formed from columns A⁻¹ l_r then (A⁻¹'s band gave only the
  // diagonal) — the same solution.
  std::mt19937 rng(23);
  for (int trial = 0; trial < 5; ++trial) {
    const test::BandMatrix a({{150, 2, true}}, rng);
    const test::RowProblem p = contactProblem(150, 80, 0.1, rng);
    const test::RowSolve deferred = solveBothWays(trial, p, a).deferred;
    EXPECT_TRUE(deferred.stats.reassembled) << trial;
    EXPECT_EQ(deferred.stats.solved_columns, p.rows.rows()) << trial;
    EXPECT_LT(deferred.stats.structured_steps, deferred.stats.newton_iterations) << trial;
  }
}

TEST(DeferredDelassus, RowsOfOtherKindsOnTheSamePointsKeepNothing) {
  // A second call on the same A whose rows lie on the same points with the same coefficients, but
  // the fixed point's three rows are a contact now: its equality rows are not the first call's,
  // so neither W_BB nor W's diagonal is held, and it solves as a fresh solver does.
  for (int trial = 0; trial < 3; ++trial) {
    std::mt19937 rng(47 + trial);
    test::BandMatrix a({{150, 2, true}}, rng);
    a.setRevision(0);
    std::mt19937 rows_rng(53 + trial);
    const test::RowProblem fixed = contactProblem(150, 80, 0.6, rows_rng);
    rows_rng.seed(53 + trial);
    const test::RowProblem touching = contactProblem(150, 80, 0.6, rows_rng, 1, /*point_as_contact=*/true);
    LagrangeMultiplierSolver::Options options;
    options.contact_tolerance = kTolerance;
    LagrangeMultiplierSolver solver(options), fresh(options);
    VecX step = VecX::Zero(fixed.problem.state_size), estimate = step, fresh_estimate = step;
    solver.solve(fixed.problem, fixed.rows, a, step);
    solver.solve(touching.problem, touching.rows, a, estimate);
    EXPECT_FALSE(solver.statistics().held || solver.statistics().block_held) << trial;
    EXPECT_TRUE(solver.statistics().converged) << trial;
    fresh.solve(touching.problem, touching.rows, a, fresh_estimate);
    const double cond = test::compliantCondition(touching, a);
    const double scale = fresh.multipliers().lpNorm<Eigen::Infinity>();
    EXPECT_LE((solver.multipliers() - fresh.multipliers()).lpNorm<Eigen::Infinity>(),
              cond * (2.0 * kTolerance + 1e2 * std::numeric_limits<double>::epsilon()) * scale)
        << trial;
  }
}

TEST(DeferredDelassus, FixedPointsAtBothEndsTakeOneEndsColumnsForTheirBlock) {
  // A second fixed point at point 140, far along the body from the first (point 3), as the clamps
  // at a catheter's two ends: W_BB's entries within each end come from A⁻¹'s band, those between
  // the ends from the columns of the first end's three rows (three band products, not six), and
  // the solution is the formed W's.
  std::mt19937 rng(41);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    const test::BandMatrix a({{150, 2, true}}, rng);
    test::RowProblem p = contactProblem(150, 80, 0.6, rng);
    p.rows.beginAnchor();
    p.rows.addAnchorPoint(140, 1.0);
    for (int axis = 0; axis < 3; ++axis) p.rows.addAnchoredRow(Vec3::Unit(axis), 0.1 * normal(rng));
    const test::RowSolve deferred = solveBothWays(trial, p, a).deferred;
    EXPECT_EQ(deferred.stats.block_products, 3) << trial;
  }
}

TEST(DeferredDelassus, TheEstimateOnTheSameWKeepsTheFirstCallsDiagonalAndEqualityBlock) {
  // A linearized implicit step solves its contacts twice through the same step matrix and rows:
  // the step, then its error estimate from another acceleration. The second call takes W's
  // diagonal and the equality rows' block W_BB (factored) as the first left them — the same bits
  // from the same A and rows, not computed again — and solves as a solver without them would
  // (the tolerance above). The fixed point's three rows lie on one point: W_BB comes from A⁻¹'s
  // band in the first call too, with no product through the band.
  std::mt19937 rng(37);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    test::BandMatrix a({{150, 2, true}}, rng);
    a.setRevision(0);  // the same operator in both calls (a step matrix's revision)
    const test::RowProblem p = contactProblem(150, 80, 0.6, rng);
    LagrangeMultiplierSolver::Options options;
    options.contact_tolerance = kTolerance;
    LagrangeMultiplierSolver solver(options);
    VecX step = VecX::Zero(p.problem.state_size);
    solver.solve(p.problem, p.rows, a, step);
    const LagrangeMultiplierSolver::Statistics first = solver.statistics();
    const VecX first_diagonal = solver.delassusDiagonal();
    EXPECT_TRUE(first.deferred && !first.held) << trial;
    EXPECT_EQ(first.block_products, 0) << trial;
    // The estimate: an acceleration off by a few percent of the rows' β.
    VecX estimate(p.problem.state_size);
    for (int i = 0; i < estimate.size(); ++i) estimate[i] = 0.05 * normal(rng);
    const VecX estimate_in = estimate;
    solver.solve(p.problem, p.rows, a, estimate);
    const LagrangeMultiplierSolver::Statistics second = solver.statistics();
    EXPECT_TRUE(second.held && second.block_held) << trial;
    EXPECT_EQ(second.block_products, 0) << trial;
    EXPECT_EQ(second.inverse_range, first.inverse_range) << trial;
    EXPECT_TRUE((solver.delassusDiagonal().array() == first_diagonal.array()).all()) << trial;
    EXPECT_TRUE(second.converged) << trial;
    // A fresh solver (nothing held, no warm start) on the estimate's problem: it computes W's
    // diagonal itself, to the same bits as the one held.
    LagrangeMultiplierSolver fresh(options);
    VecX fresh_estimate = estimate_in;
    fresh.solve(p.problem, p.rows, a, fresh_estimate);
    EXPECT_FALSE(fresh.statistics().held || fresh.statistics().block_held) << trial;
    EXPECT_TRUE((solver.delassusDiagonal().array() == fresh.delassusDiagonal().array()).all()) << trial;
    const double cond = test::compliantCondition(p, a);
    const double scale = fresh.multipliers().lpNorm<Eigen::Infinity>();
    const double difference = (solver.multipliers() - fresh.multipliers()).lpNorm<Eigen::Infinity>();
    std::printf("  trial %d: estimate's multipliers %.2g apart relative (cond(W + R) %.2g)\n", trial,
                difference / scale, cond);
    EXPECT_LE(difference, cond * (2.0 * kTolerance + 1e2 * std::numeric_limits<double>::epsilon()) * scale) << trial;
  }
}

}  // namespace
}  // namespace filum::constraints
