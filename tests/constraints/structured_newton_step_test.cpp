// The contact Newton's steps solved through A's band (AugmentedNewtonSystem) against the dense
// LU of J_SS, on contact problems W = L A⁻¹ Lᵀ built from a random symmetric positive definite
// block band A (a thread's step matrix: 3 × 3 blocks, neighbours within two points) and rows of
// contacts on two to four consecutive points (a spline point against an obstacle), some between
// points 15 apart on the thread (+w on one side, −w on the other: self-contacts), μ = 0.3, and an
// equality row (a fixed point). The augmented system's Schur complement is J_SS exactly, so both
// take the same Newton steps up to round-off: the same iterations, and multipliers that agree to
// the solve's own tolerance (1e-12 relative) times cond(W + R) (below 1e3 here: fewer rows than
// coordinates, A well conditioned), checked at 1e-8.
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "filum/constraints/contact_newton.hpp"

namespace filum::constraints {
namespace {

/// A block band matrix A exposed as BandBlocks (no solves: ContactNewton only reads the band).
class BandMatrix final : public BlockInverse {
 public:
  BandMatrix(int groups, int range, std::mt19937& rng) : groups_(groups), range_(range) {
    std::normal_distribution<double> normal(0.0, 1.0);
    blocks_.assign(static_cast<std::size_t>(groups) * (range + 1), Eigen::Matrix3d::Zero());
    dense_ = MatX::Zero(3 * groups, 3 * groups);
    for (int i = 0; i < groups; ++i)
      for (int j = std::max(0, i - range); j < i; ++j) {
        Eigen::Matrix3d b;
        for (int a = 0; a < 3; ++a)
          for (int c = 0; c < 3; ++c) b(a, c) = 0.3 * normal(rng);
        dense_.block<3, 3>(3 * i, 3 * j) = b;
        dense_.block<3, 3>(3 * j, 3 * i) = b.transpose();
      }
    // Diagonally dominant: symmetric positive definite.
    for (int i = 0; i < 3 * groups; ++i) dense_(i, i) = dense_.row(i).cwiseAbs().sum() + 1.0;
    for (int i = 0; i < groups; ++i)
      for (int j = std::max(0, i - range); j <= i; ++j) blocks_[i * (range + 1) + (j - i + range)] = dense_.block<3, 3>(3 * i, 3 * j);
    for (int i = 0; i < groups; ++i) point_group_.push_back(i);
  }
  void solveBlock(int, Eigen::Ref<VecX>) const override {}
  bool bandBlocks(int body, BandBlocks& out) const override {
    if (body != 0) return false;
    out.groups = groups_;
    out.range = range_;
    out.lower = blocks_.data();
    out.point_group = point_group_.data();
    return true;
  }
  const MatX& dense() const { return dense_; }

 private:
  int groups_, range_;
  std::vector<Eigen::Matrix3d> blocks_;
  std::vector<int> point_group_;
  MatX dense_;
};

TEST(StructuredNewtonStep, TakesTheDenseLusStepsThroughTheBand) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  const int points = 300;
  int structured_trials = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const BandMatrix a(points, 2, rng);
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
    const MatX w = l * a.dense().ldlt().solve(l.transpose());
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
