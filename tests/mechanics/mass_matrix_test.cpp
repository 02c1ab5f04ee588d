// The constant mass matrix of the dynamic spline (paper eq. 3) and the O(n) band solve.
#include <gtest/gtest.h>

#include <iostream>
#include <limits>
#include <memory>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "filum/geometry/nonuniform_bspline.hpp"
#include "filum/geometry/uniform_cubic_bspline.hpp"
#include "filum/mechanics/banded_cholesky.hpp"
#include "filum/mechanics/mass_matrix.hpp"
#include "filum/mechanics/scalar_band.hpp"
#include "support/finite_difference.hpp"

namespace filum::mechanics {
namespace {

TEST(MassMatrix, EntriesSumToTheThreadMass) {
  // Σ_ij M_ij = m ∫ (Σ_i b_i)(Σ_j b_j) ds = m ∫ 1 ds = m (partition of unity). The quadrature is
  // exact, so only round-off of ~16 n² additions remains: 1e-12 relative is far above it.
  for (int n : {4, 5, 13, 30, 165}) {
    const double mass = 2.86e-6;
    const SparseMatrix M = massMatrix(geometry::UniformCubicBSpline(n), mass);
    EXPECT_NEAR(M.sum(), mass, 1e-12 * mass) << "n = " << n;
  }
}

TEST(MassMatrix, IsSymmetricPositiveDefiniteAndBandedWithBandwidthSeven) {
  const int n = 30;
  const SparseMatrix M = massMatrix(geometry::UniformCubicBSpline(n), 1.0);
  const MatX dense = MatX(M);
  EXPECT_EQ((dense - dense.transpose()).cwiseAbs().maxCoeff(), 0.0);
  Eigen::SelfAdjointEigenSolver<MatX> eig(dense);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
  // Bandwidth w = 2l − 1 = 7 for locality l = 4 (paper §3): |i − j| <= 3 and the outermost
  // diagonal is really occupied.
  int widest = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (dense(i, j) != 0.0) widest = std::max(widest, std::abs(i - j));
  EXPECT_EQ(2 * widest + 1, 7);
}

TEST(MassMatrix, InteriorEntriesMatchTheClosedForm) {
  // For the uniform cubic B-spline with N segments the interior rows of ∫ b_i b_j ds are
  // (1/N)·(1/5040)·[1, 120, 1191, 2416, 1191, 120, 1] (integrals of products of cubic B-splines).
  const int n = 20, N = n - 3;
  const MatX M = MatX(massMatrix(geometry::UniformCubicBSpline(n), 1.0));
  const double expected[4] = {2416.0, 1191.0, 120.0, 1.0};
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(M(10, 10 + k), expected[k] / 5040.0 / N, 1e-15);
}

TEST(BandedCholesky, SolvesLikeADenseCholesky) {
  // Backward-stable Cholesky: relative residual ~ κ(M) ε; κ(M) < 20 for the B-spline mass
  // matrix, so 1e-13 leaves a wide margin.
  const int n = 50;
  const SparseMatrix M = massMatrix(geometry::UniformCubicBSpline(n), 0.3);
  const BandedCholesky band(M, 3);
  const Points B = test::randomPoints(n, 1.0, 7);
  Points X = B;
  band.solve(X);
  const Points reference = MatX(M).llt().solve(MatX(B));
  EXPECT_LE((X - reference).norm(), 1e-13 * reference.norm());
  EXPECT_LE((M * X - B).norm(), 1e-13 * B.norm());
}

TEST(BandedCholesky, RefusesAnIndefiniteMatrix) {
  SparseMatrix A(2, 2);
  A.insert(0, 0) = 1.0;
  A.insert(1, 1) = -1.0;
  EXPECT_THROW(BandedCholesky(A, 1), std::runtime_error);
}

TEST(GravityForce, AFreeThreadFallsAtExactlyG) {
  // M A = Q with Q_i = m g ∫ b_i ds: A = g 1 solves it exactly since Σ_j M_ij = m ∫ b_i ds, so
  // every control point accelerates at g up to the solve's round-off (κ ε ≈ 1e-15 g).
  const int n = 30;
  const double mass = 1e-3;
  const geometry::UniformCubicBSpline basis(n);
  const SparseMatrix M = massMatrix(basis, mass);
  const VecX w = basisIntegrals(basis);
  const Vec3 g(0.0, 0.0, -9.81);
  Points B(n, 3);
  for (int i = 0; i < n; ++i) B.row(i) = mass * w[i] * g.transpose();
  BandedCholesky(M, 3).solve(B);
  // The banded Cholesky solve is backward stable (Higham, Accuracy and Stability, Thm 10.4 with
  // §7.2): componentwise, |x̂ − x| <= γ · cond(M, x) · |x| with γ ≈ (band width 7) ε and Skeel's
  // condition number cond(M, x) = ‖ |M⁻¹| |M| |x| ‖∞ / ‖x‖∞, computed here (the exact x is the
  // constant g, so cond(M, x) = ‖ |M⁻¹| |M| ‖∞ ≈ 317 for n = 30, below the normwise
  // κ₂(M) ≈ 1.4e3 that the end basis functions, cut by the curve's ends, give). The bound,
  // 4.8e-12 m/s², is what this a-priori analysis allows; the error measured is ~1e-15 (the bound
  // asserted before was 1e-10).
  const Eigen::MatrixXd dense(M);
  const Eigen::MatrixXd skeel = dense.inverse().cwiseAbs() * dense.cwiseAbs();
  const double cond = skeel.rowwise().sum().maxCoeff();
  const double bound = 7.0 * cond * std::numeric_limits<double>::epsilon() * g.norm();
  std::cout << "  cond(M, x) = " << cond << ", bound " << bound << " m/s^2\n";
  for (int i = 0; i < n; ++i) EXPECT_LE((B.row(i).transpose() - g).norm(), bound) << "control point " << i;
}

}  // namespace
}  // namespace filum::mechanics

namespace filum {
namespace {

TEST(ScalarBand, ProductsEqualTheSparseMatrixProducts) {
  // The band product sums the same entries in another order: equal to a few ulps of the row's
  // |A| |x| (≤ 2r + 1 terms, each rounded once: (2r + 1) ε relative is asserted). Cubic bands
  // of 40 points take the fixed-size interior path (r = 3), 6 cubic points and a quadratic NUBS
  // the row-by-row one.
  std::vector<std::unique_ptr<CurveBasis>> bases;
  bases.push_back(std::make_unique<geometry::UniformCubicBSpline>(40));
  bases.push_back(std::make_unique<geometry::UniformCubicBSpline>(6));
  bases.push_back(std::make_unique<geometry::NonUniformBSpline>(2, std::vector<double>{0, 0, 0, 1, 2, 2.5, 4, 5, 5, 5}));
  for (const auto& basis : bases) {
    const int n = basis->controlPointCount(), r = basis->degree();
    const SparseMatrix M = mechanics::massMatrix(*basis, 0.3);
    const mechanics::ScalarBand band(M, r);
    const Points x = Points::Random(n, 3);
    Points y(n, 3), z = Points::Ones(n, 3);
    band.multiply(x, y);
    const Points expected = M * x;
    const double bound = (2 * r + 1) * std::numeric_limits<double>::epsilon() * (M.cwiseAbs() * x.cwiseAbs()).maxCoeff();
    EXPECT_LE((y - expected).cwiseAbs().maxCoeff(), bound) << n << " points of degree " << r;
    band.subtractProduct(x, z);
    EXPECT_LE((z - (Points::Ones(n, 3) - expected)).cwiseAbs().maxCoeff(), 2 * bound) << n << " points of degree " << r;
  }
  const SparseMatrix M = mechanics::massMatrix(*bases.front(), 0.3);
  EXPECT_THROW(mechanics::ScalarBand(M, 2), std::logic_error);  // entries 3 apart do not fit
}

}  // namespace
}  // namespace filum
