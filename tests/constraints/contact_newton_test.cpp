// ContactNewton (semismooth Newton on the Alart–Curnier function) on contact problems whose
// solutions are known in closed form, on random problems against the laws themselves, and on a
// redundant (singular) Delassus matrix made solvable by compliance.
//
// Tolerances: the solve is asked for a residual of 1e-12 relative (contact_newton.hpp: against
// max(|β|∞, max_r |λ_r| W_rr)); Newton converges quadratically once the active set is found, so it
// gets there or to round-off (1e-16 × the condition number of these matrices, at most 1e3).
// Multipliers are then checked to 1e-9 relative, a margin over cond × 1e-12.
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "filum/constraints/contact_newton.hpp"

namespace filum::constraints {
namespace {

constexpr double kTolerance = 1e-12;

/// Rows for `contacts` contacts (normal, and a friction pair when μ > 0) on dummy anchors:
/// ContactNewton reads only their kinds and μ.
ConstraintRows contactRows(int contacts, double mu) {
  ConstraintRows rows;
  rows.clear();
  for (int i = 0; i < contacts; ++i) {
    rows.beginAnchor();
    rows.addAnchorPoint(i, 1.0);
    rows.addContactRows(Vec3::UnitZ(), 0.0, mu, Vec3::UnitX(), 0.0, Vec3::UnitY(), 0.0);
  }
  return rows;
}

struct Solved {
  VecX lambda;
  ContactNewton::Result result;
};

Solved solve(const MatX& w, const VecX& beta, const ConstraintRows& rows, double compliance = 0.0) {
  ContactNewton newton;
  ContactNewton::Settings settings;
  Solved out;
  out.lambda = VecX::Zero(beta.size());
  const VecX r = compliance * w.diagonal();
  out.result = newton.solve(w, beta, r, rows, settings, kTolerance, out.lambda);
  return out;
}

TEST(ContactNewton, SingleNormalRowPushesOrLetsGo) {
  const ConstraintRows rows = contactRows(1, 0.0);
  const MatX w = MatX::Constant(1, 1, 2.0);
  // β > 0: the contact must push, W λ = β.
  Solved pushed = solve(w, VecX::Constant(1, 1.0), rows);
  ASSERT_TRUE(pushed.result.converged);
  EXPECT_NEAR(pushed.lambda[0], 0.5, 1e-12);
  // β < 0: separating, no force.
  Solved apart = solve(w, VecX::Constant(1, -1.0), rows);
  ASSERT_TRUE(apart.result.converged);
  EXPECT_EQ(apart.lambda[0], 0.0);
}

TEST(ContactNewton, FrictionSticksInsideTheDiscAndSlidesOnItsRim) {
  const ConstraintRows rows = contactRows(1, 0.5);
  const MatX w = MatX::Identity(3, 3);
  // Normal push 1; a tangential demand of 0.3 is inside the disc (μ λ_n = 0.5): stick, λ_t = β_t.
  VecX beta(3);
  beta << 1.0, 0.3, 0.0;
  Solved stick = solve(w, beta, rows);
  ASSERT_TRUE(stick.result.converged);
  EXPECT_NEAR(stick.lambda[1], 0.3, 1e-12);
  // A demand of (3, 4): outside, the force lies on the rim, opposite the slip w_t = λ_t − β_t:
  // λ_t = μ λ_n (3, 4)/5.
  beta << 1.0, 3.0, 4.0;
  Solved slide = solve(w, beta, rows);
  ASSERT_TRUE(slide.result.converged);
  // The solve stops at |F| <= kTolerance |β|∞ (4 here); with W = I its Jacobian is the identity on
  // a sliding pair too, so λ's error is F's (a chord step stops just below the threshold, where
  // Newton's quadratic step would land at round-off).
  const double bound = kTolerance * 4.0;
  EXPECT_NEAR(slide.lambda[0], 1.0, bound);
  EXPECT_NEAR(slide.lambda[1], 0.5 * 0.6, bound);
  EXPECT_NEAR(slide.lambda[2], 0.5 * 0.8, bound);
}

/// The laws at λ: Signorini and Coulomb with maximal dissipation, to `tol` (absolute, m/s² and N).
void expectCoulomb(const MatX& w, const VecX& beta, const ConstraintRows& rows, const VecX& lambda, double tol) {
  const VecX a = w * lambda - beta;
  for (int r = 0; r < rows.rows(); r += 3) {
    EXPECT_GE(lambda[r], -tol);
    EXPECT_GE(a[r], -tol);
    EXPECT_LE(std::min(std::abs(lambda[r]), std::abs(a[r])), tol) << "complementarity, contact " << r / 3;
    const double mu = rows.friction(r + 1);
    const Eigen::Vector2d lt(lambda[r + 1], lambda[r + 2]), at(a[r + 1], a[r + 2]);
    EXPECT_LE(lt.norm(), mu * lambda[r] + tol);
    if (lt.norm() < mu * lambda[r] - tol) {
      EXPECT_LE(at.norm(), tol) << "stick, contact " << r / 3;
    } else if (at.norm() > tol) {
      EXPECT_NEAR(lt.dot(at), -lt.norm() * at.norm(), tol * (1.0 + lt.norm() * at.norm())) << "slip opposes";
    }
  }
}

/// W = J Jᵀ/c + I/10 for a random c × c J (positive definite, eigenvalues in [0.1, ~4]).
MatX randomDelassus(int c, std::mt19937& rng, std::normal_distribution<double>& normal) {
  MatX j(c, c);
  for (int i = 0; i < c; ++i)
    for (int k = 0; k < c; ++k) j(i, k) = normal(rng);
  return j * j.transpose() / c + 0.1 * MatX::Identity(c, c);
}

TEST(ContactNewton, RandomProblemsSatisfyTheLaws) {
  // W = J Jᵀ + I/10 of random 3-row contacts, β random: some contacts push, some open, some slide.
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const int contacts = 2 + trial % 5, c = 3 * contacts;
    const MatX w = randomDelassus(c, rng, normal);
    VecX beta(c);
    for (int i = 0; i < c; ++i) beta[i] = normal(rng);
    const ConstraintRows rows = contactRows(contacts, 0.3);
    const Solved s = solve(w, beta, rows);
    ASSERT_TRUE(s.result.converged) << "trial " << trial << " residual " << s.result.residual;
    // The residual bound 1e-12 × scale, times the row scaling (W_rr <= ~3 here), as absolute slack.
    expectCoulomb(w, beta, rows, s.lambda, 1e-9 * std::max(1.0, s.lambda.lpNorm<Eigen::Infinity>()));
  }
}

TEST(ContactNewton, RedundantContactsSolveWithCompliance) {
  // Two identical contacts (the same row twice: W singular) asked for different accelerations:
  // without compliance the higher demand wins and the split of λ between the two is arbitrary;
  // with compliance R = ε W_rr the problem of W + R has one solution, and the acceleration the
  // two rows give is the higher demand to within R λ.
  ConstraintRows rows = contactRows(2, 0.0);
  MatX w(2, 2);
  w << 1.0, 1.0, 1.0, 1.0;
  VecX beta(2);
  beta << 1.0, 2.0;
  const double epsilon = 1e-6;
  const Solved s = solve(w, beta, rows, epsilon);
  ASSERT_TRUE(s.result.converged) << s.result.residual;
  // Row 2 is active: (W λ)_2 + ε λ_2 = 2; row 1 then sees 2 − ε λ_2 > 1: it opens, λ_1 = 0.
  EXPECT_EQ(s.lambda[0], 0.0);
  // |F| <= kTolerance · max(|β|∞, λ_2 (W_22 + R_22)) = 2 kTolerance, and row 2's Jacobian is 1.
  EXPECT_NEAR(s.lambda[1], 2.0 / (1.0 + epsilon), 2.0 * kTolerance);
}

TEST(ContactNewton, ChordStepsOnTheLastFactorizationReachTheSameSolution) {
  // The second solve of a linearized implicit step: the same W and rows (the same matrix_key),
  // a right-hand side moved a little, the first solve's λ as warm start. Its steps may be taken
  // on the first solve's last factorization (chord steps); the solution is the problem's own:
  // the same λ as a solve that carries nothing over, to the solves' accuracy (cond(W) × the
  // tolerance, cond(W) <= 1e2 here, asserted: 1e-9 relative leaves a margin), and the laws hold.
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  int chords = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const int contacts = 3 + trial % 4, c = 3 * contacts;
    const MatX w = randomDelassus(c, rng, normal);
    // The tolerance's premise: cond(W) <= 1e2.
    const Eigen::SelfAdjointEigenSolver<MatX> spectrum(w);
    ASSERT_LE(spectrum.eigenvalues().maxCoeff() / spectrum.eigenvalues().minCoeff(), 1e2) << "trial " << trial;
    VecX beta(c), moved(c);
    for (int i = 0; i < c; ++i) beta[i] = normal(rng);
    for (int i = 0; i < c; ++i) moved[i] = beta[i] + 1e-3 * normal(rng);  // the estimate's correction
    const ConstraintRows rows = contactRows(contacts, 0.3);
    const VecX compliance = VecX::Zero(c);
    ContactNewton::Settings settings;
    settings.matrix_key = 5;
    ContactNewton carried;
    VecX lambda = VecX::Zero(c);
    ASSERT_TRUE(carried.solve(w, beta, compliance, rows, settings, kTolerance, lambda).converged);
    const VecX start = lambda;
    const ContactNewton::Result second = carried.solve(w, moved, compliance, rows, settings, kTolerance, lambda);
    ASSERT_TRUE(second.converged) << "trial " << trial << " residual " << second.residual;
    chords += second.chord_steps;
    ContactNewton fresh;
    VecX reference = start;
    ASSERT_TRUE(fresh.solve(w, moved, compliance, rows, ContactNewton::Settings(), kTolerance, reference).converged);
    EXPECT_LE((lambda - reference).lpNorm<Eigen::Infinity>(), 1e-9 * std::max(1.0, reference.lpNorm<Eigen::Infinity>()))
        << "trial " << trial;
    expectCoulomb(w, moved, rows, lambda, 1e-9 * std::max(1.0, lambda.lpNorm<Eigen::Infinity>()));
    // Under a new key nothing is carried over: the same iterates as the solver that never held
    // a factorization, bit for bit.
    settings.matrix_key = 6;
    VecX again = start;
    carried.solve(w, moved, compliance, rows, settings, kTolerance, again);
    EXPECT_TRUE(again == reference) << "trial " << trial;
  }
  // Most of these second solves keep their active set: chords are taken (counted, not assumed).
  EXPECT_GT(chords, 0);
}

}  // namespace
}  // namespace filum::constraints
