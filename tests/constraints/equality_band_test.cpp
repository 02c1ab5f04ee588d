// Equality rows solved through A's band (lagrange_multiplier_solver.hpp: solveEqualitiesThroughBand
// and, with contacts, the equality block's steps): the augmented system [A −L_Bᵀ; L_B 0] by its
// envelope LU against W = L A⁻¹ Lᵀ formed and factored ("newton_linear_solve": "dense"), on rows
// like a ChannelConstraint's — two rows across a random direction at each of many points of a
// rod-like body (test::BandMatrix: points interleaved with frames, neighbours within two groups).
//
// Tolerance. Both are backward stable solves of W λ = β. The band route eliminates A's points
// (positive definite pivots) and then each row after its points, whose pivot is the Schur
// complement of the rows before it, a pivot of W's own LDLᵀ (positive for independent rows): no
// growth beyond that of a Cholesky factorization, whose backward error is γ_{3n} |L||Lᵀ| (Higham,
// Accuracy and Stability of Numerical Algorithms, 2002, Thm 10.3), n the system's order. Two
// solutions then differ by at most 2 cond(W) γ_{3n} relative, with cond(W) computed per problem
// and n = 3 (groups) + c, the augmented system's order.
#include <cstdio>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>

#include "filum/constraints/lagrange_multiplier_solver.hpp"
#include "support/row_problem.hpp"

namespace filum::constraints {
namespace {

/// Two rows across a random unit direction at each of `held` consecutive points from point 1
/// (a body held along a channel), then `contacts` contacts on points (k, k + 1) beyond them, 4
/// points apart (held + 4 contacts + 4 <= points).
test::RowProblem channelProblem(int points, int held, int contacts, std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  test::RowProblem out(points);
  ConstraintRows& rows = out.rows;
  for (int p = 1; p <= held; ++p) {
    Vec3 t(normal(rng), normal(rng), normal(rng));
    t.normalize();
    const Vec3 u = t.unitOrthogonal(), w = t.cross(u);
    rows.beginAnchor();
    rows.addAnchorPoint(p, 1.0);
    rows.addAnchoredRow(u, normal(rng));
    rows.addAnchoredRow(w, normal(rng));
  }
  for (int k = 0; k < contacts; ++k) {
    const int first = held + 2 + 4 * k + static_cast<int>(rng() % 3);  // distinct pairs: no redundant rows
    Vec3 n(normal(rng), normal(rng), normal(rng));
    n.normalize();
    const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    rows.beginAnchor();
    rows.addAnchorPoint(first, 0.5);
    rows.addAnchorPoint(first + 1, 0.5);
    rows.addContactRows(n, std::abs(normal(rng)), 0.3, t1, normal(rng), t2, normal(rng));
  }
  return out;
}

constexpr double kTolerance = 1e-12;  // τ, the contact solve's relative residual

test::RowSolve solve(const test::RowProblem& p, const test::BandMatrix& a, bool through_band) {
  return test::solveRows(p, a, through_band, kTolerance);  // false: W formed and factored
}

/// 2 cond γ_{3n} (see the header), n the augmented system's order over `groups` 3 × 3 groups.
double roundOff(double cond, const test::RowProblem& p, int groups) {
  const double n = 3.0 * groups + p.rows.rows();
  const double u = std::numeric_limits<double>::epsilon() / 2;
  return 2.0 * cond * (3 * n * u / (1 - 3 * n * u));
}

/// The two solutions' relative distance, printed and checked against `allowed`.
void expectClose(int trial, const test::RowProblem& p, const test::RowSolve& band, const test::RowSolve& formed,
                 double allowed) {
  const double difference = (band.lambda - formed.lambda).lpNorm<Eigen::Infinity>();
  const double scale = formed.lambda.lpNorm<Eigen::Infinity>();
  std::printf("  trial %d: %d rows, multipliers %.2g apart relative (allowed %.2g)\n", trial, p.rows.rows(),
              difference / scale, allowed);
  EXPECT_LE(difference, allowed * scale) << trial;
}

TEST(EqualityBand, HeldAlongAChannelSolvesAsTheFormedW) {
  // 150 points with their frames (300 groups), 120 of them held: 240 rows, W never formed.
  std::mt19937 rng(31);
  for (int trial = 0; trial < 4; ++trial) {
    const test::BandMatrix a({{150, 2, true}}, rng);
    const test::RowProblem p = channelProblem(150, 120, 0, rng);
    const test::RowSolve band = solve(p, a, true), formed = solve(p, a, false);
    EXPECT_TRUE(band.stats.equality_band) << trial;
    EXPECT_FALSE(formed.stats.equality_band) << trial;
    EXPECT_FALSE(band.stats.reassembled) << trial;
    EXPECT_EQ(band.stats.solved_columns, 0) << trial;
    expectClose(trial, p, band, formed, roundOff(test::condition(test::delassus(p.rows, a, p.problem)), p, 300));
  }
}

TEST(EqualityBand, AnIndefiniteStepMatrixIsLeftToWFactoredWithPivoting) {
  // A with a negative pivot (the first group's diagonal negated: a compressed thread's step matrix
  // is indefinite). The envelope LU does not pivot, so it refuses a pivot <= 0, and W is formed
  // and factored densely with pivoting (not by the sparse factorization, which pivots for
  // sparsity only). No row acts on that group, so W itself is definite here, and the dense
  // pivoted LDLᵀ is backward stable on it: λ within 2 cond(W) γ_{3n} of W⁻¹ β by a full-pivot LU.
  std::mt19937 rng(41);
  for (int trial = 0; trial < 2; ++trial) {
    const test::BandMatrix a({{150, 2, true, /*indefinite=*/true}}, rng);
    const test::RowProblem p = channelProblem(150, 120, 0, rng);
    const test::RowSolve band = solve(p, a, true);
    EXPECT_FALSE(band.stats.equality_band) << trial;
    EXPECT_FALSE(band.stats.sparse) << trial;
    const MatX w = test::delassus(p.rows, a, p.problem);
    VecX beta(p.rows.rows());
    for (int r = 0; r < p.rows.rows(); ++r) beta[r] = p.rows.rhs(r);  // a_t = 0
    test::RowSolve reference = band;
    reference.lambda = w.fullPivLu().solve(beta);
    expectClose(trial, p, band, reference, roundOff(test::condition(w), p, 300));
  }
}

TEST(EqualityBand, WithContactsTheEqualityStepsGoThroughTheBand) {
  // The same held rows and 6 contacts beyond them: the contact Newton's equality block (its
  // Gauss–Seidel steps and the polish) through the augmented system of the held rows. Both
  // solves reach the contact tolerance τ; the difference allowed is that of two such solutions,
  // cond(W + R) (2τ + 2 γ_{3n}) relative (deferred_delassus_test.cpp's argument), R = 1e-6 W_rr on
  // the contact rows (the solver's default compliance).
  std::mt19937 rng(37);
  for (int trial = 0; trial < 4; ++trial) {
    const test::BandMatrix a({{150, 2, true}}, rng);
    const test::RowProblem p = channelProblem(150, 120, 6, rng);
    const test::RowSolve band = solve(p, a, true), formed = solve(p, a, false);
    EXPECT_TRUE(band.stats.converged) << trial;
    EXPECT_TRUE(formed.stats.converged) << trial;
    EXPECT_TRUE(band.stats.equality_block_band) << trial;
    EXPECT_FALSE(formed.stats.equality_block_band) << trial;
    const double cond = test::compliantCondition(p, a);
    expectClose(trial, p, band, formed, cond * 2.0 * kTolerance + roundOff(cond, p, 300));
  }
}

}  // namespace
}  // namespace filum::constraints
