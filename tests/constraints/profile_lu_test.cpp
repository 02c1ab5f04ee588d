// ProfileLu (constraints/profile_lu.hpp): the envelope LU without pivoting against Eigen's dense
// LU with partial pivoting, on non-symmetric matrices with a random symmetric envelope (fill
// inside it from elimination), diagonally dominant by rows so that no pivoting is needed and the
// condition number stays below 10: both solutions then agree to n ε cond (round-off of two
// backward-stable eliminations), far below the 1e-12 asked.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/LU>

#include "filum/constraints/profile_lu.hpp"

namespace filum::constraints {
namespace {

TEST(ProfileLu, SolvesLikeADenseLuInsideARandomEnvelope) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  ProfileLu lu;
  for (int n : {1, 2, 5, 40, 200}) {
    for (int trial = 0; trial < 3; ++trial) {
      MatX k = MatX::Zero(n, n);
      std::vector<int> first(n);
      for (int i = 0; i < n; ++i) first[i] = std::max(0, i - static_cast<int>(rng() % 12));
      if (n > 10) first[n - 1] = 0;  // a long-range coupling, as a contact between far parts of a thread
      lu.reset(n);
      for (int i = 0; i < n; ++i)
        for (int j = first[i]; j < i; ++j) {
          if (rng() % 3 == 0) continue;  // zeros inside the envelope: filled by elimination
          k(i, j) = value(rng);
          k(j, i) = value(rng);
          lu.widen(i, j);
        }
      for (int i = 0; i < n; ++i) k(i, i) = 2.0 * (k.row(i).cwiseAbs().sum() + k.col(i).cwiseAbs().sum()) + 1.0;
      lu.allocate();
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          if (k(i, j) != 0.0) lu.at(i, j) = k(i, j);
      ASSERT_TRUE(lu.factor());
      const VecX b = VecX::Random(n);
      VecX x = b;
      lu.solve(x);
      const VecX reference = k.partialPivLu().solve(b);
      EXPECT_LE((x - reference).lpNorm<Eigen::Infinity>(), 1e-12 * reference.lpNorm<Eigen::Infinity>()) << n;
    }
  }
}

TEST(ProfileLu, RefusesAZeroPivot) {
  ProfileLu lu;
  lu.reset(2);
  lu.widen(1, 0);
  lu.allocate();
  lu.at(0, 0) = 1.0;
  lu.at(0, 1) = 2.0;
  lu.at(1, 0) = 1.0;
  lu.at(1, 1) = 2.0;  // rank 1
  EXPECT_FALSE(lu.factor());
}

TEST(ProfileLu, CostIsTheEnvelopesSumOfSquares) {
  ProfileLu lu;
  lu.reset(4);
  lu.widen(3, 0);
  lu.widen(2, 1);
  EXPECT_DOUBLE_EQ(lu.cost(), 9.0 + 1.0);
}

}  // namespace
}  // namespace filum::constraints
