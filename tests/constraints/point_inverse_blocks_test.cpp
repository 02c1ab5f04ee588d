// PointInverseBlocks: H's blocks are (A⁻¹)_pq between the rows' points, and the same bits
// whatever order the points arrived in (a run restored from a saved state must repeat bit for
// bit while the cache holds other points than it did). A = a random symmetric positive definite
// matrix over one body of 12 points, solved densely; its inverse formed by Eigen is the
// reference. A is diagonally dominant by 1 with off-diagonal entries ~0.1 (its eigenvalues lie
// between 1 and about 8), so both inverses agree to ε cond(A) |A⁻¹| ~ 1e-15: asserted at 1e-13.
#include <random>

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "filum/constraints/point_inverse_blocks.hpp"

namespace filum::constraints {
namespace {

class DenseInverse final : public BlockInverse {
 public:
  explicit DenseInverse(const MatX& a) : factor_(a) {}
  void solveBlock(int, Eigen::Ref<VecX> x) const override { x = factor_.solve(VecX(x)); }
  long revision() const override { return 0; }

 private:
  Eigen::LLT<MatX> factor_;
};

/// Rows of one term each on the given points.
ConstraintRows rowsOn(const std::vector<int>& points) {
  ConstraintRows rows;
  rows.clear();
  for (int p : points) {
    rows.addTerm(p, Vec3(1.0, 0.0, 0.0));
    rows.endRow(0.0);
  }
  return rows;
}

TEST(PointInverseBlocks, HoldTheInverseBetweenPointsWhateverTheirOrder) {
  const int n = 12;
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  MatX a(3 * n, 3 * n);
  for (int i = 0; i < 3 * n; ++i)
    for (int j = 0; j <= i; ++j) a(i, j) = a(j, i) = 0.1 * normal(rng);
  for (int i = 0; i < 3 * n; ++i) a(i, i) = a.row(i).cwiseAbs().sum() + 1.0;  // diagonally dominant
  const MatX inverse = a.inverse();
  const DenseInverse operator_a(a);
  ConstraintProblem problem;
  problem.bodies = {BodyBlock{0, n}};
  problem.dof_points = n;
  problem.state_size = 3 * n;
  problem.layout_revision = 0;
  const std::vector<int> point_body(n, 0);

  // One cache takes 9 and 4, then 7 and 4; the other 7, then 4 and 9.
  PointInverseBlocks first, second;
  for (const std::vector<int>& call : {std::vector<int>{9, 4}, std::vector<int>{7, 4}}) {
    first.keepIfUnchanged(operator_a, problem);
    first.listMissing(rowsOn(call));
    ASSERT_TRUE(first.addMissing(operator_a, problem, point_body));
  }
  for (const std::vector<int>& call : {std::vector<int>{7}, std::vector<int>{4, 9}}) {
    second.keepIfUnchanged(operator_a, problem);
    second.listMissing(rowsOn(call));
    ASSERT_TRUE(second.addMissing(operator_a, problem, point_body));
  }
  ASSERT_EQ(first.held(), 3);
  ASSERT_EQ(second.held(), 3);
  for (int p : {4, 7, 9})
    for (int q : {4, 7, 9}) {
      const Eigen::Matrix3d one = first.block(first.slot(p), first.slot(q));
      const Eigen::Matrix3d other = second.block(second.slot(p), second.slot(q));
      EXPECT_EQ(one, other) << "points " << p << ", " << q;
      EXPECT_LE((one - inverse.block<3, 3>(3 * p, 3 * q)).norm(), 1e-13) << "points " << p << ", " << q;
    }
  // Another operator forgets every point.
  first.keepIfUnchanged(DenseInverse(a), problem);
  EXPECT_EQ(first.held(), 0);
}

}  // namespace
}  // namespace filum::constraints
