#include "filum/mechanics/block_band_ldlt.hpp"

#include <algorithm>
#include <cmath>


namespace filum::mechanics {

void BlockBandLdlt::resize(int points, int range) {
  n_ = points;
  r_ = std::max(0, std::min(range, n_ - 1));
  width_ = r_ + 1;
  blocks_.assign(static_cast<std::size_t>(n_) * width_, Eigen::Matrix3d::Zero());
  reciprocals_.assign(n_, Eigen::Vector3d::Zero());
  work_.assign(width_, Eigen::Matrix3d::Zero());
}

void BlockBandLdlt::setZero() {
  for (Eigen::Matrix3d& b : blocks_) b.setZero();
}

namespace {

// A 3 × 3 pivot block D = l δ lᵀ (unit lower l, diagonal δ) stored in place: δ on the diagonal,
// l below it — the scalar LDLᵀ of the block, so that the whole factorization does the arithmetic
// of the scalar band LDLᵀ (an explicit inverse of D would lose cond(D) ε: D mixes the axial
// stiffness h²EA with the mass, cond up to 1e8 for a real suture at large steps).
bool factorPivot(Eigen::Matrix3d& d) {
  const double d0 = d(0, 0);
  if (!(std::abs(d0) > 0.0) || !std::isfinite(d0)) return false;
  const double l10 = d(1, 0) / d0, l20 = d(2, 0) / d0;
  const double d1 = d(1, 1) - l10 * l10 * d0;
  if (!(std::abs(d1) > 0.0) || !std::isfinite(d1)) return false;
  const double l21 = (d(2, 1) - l20 * l10 * d0) / d1;
  const double d2 = d(2, 2) - l20 * l20 * d0 - l21 * l21 * d1;
  if (!(std::abs(d2) > 0.0) || !std::isfinite(d2)) return false;
  d << d0, 0.0, 0.0, l10, d1, 0.0, l20, l21, d2;
  return true;
}

// x := D⁻¹ x with D factored by factorPivot, `reciprocal` holding 1/δ (a product instead of a
// division per coordinate in every solve: one more rounding, far below the pivot's own).
template <typename Vector>
void solvePivot(const Eigen::Matrix3d& f, const Eigen::Vector3d& reciprocal, Vector&& x) {
  x[1] -= f(1, 0) * x[0];
  x[2] -= f(2, 0) * x[0] + f(2, 1) * x[1];
  x[0] *= reciprocal[0];
  x[1] *= reciprocal[1];
  x[2] *= reciprocal[2];
  x[1] -= f(2, 1) * x[2];
  x[0] -= f(1, 0) * x[1] + f(2, 0) * x[2];
}

}  // namespace

std::string BlockBandLdlt::factor() {
  for (int i = 0; i < n_; ++i) {
    const int first = std::max(0, i - r_);
    // W_ij = A_ij − Σ_k W_ik L_jkᵀ,  L_ij = W_ij D_j⁻¹ (row by row: D_j is symmetric), work_
    // keeps W_ij.
    for (int j = first; j < i; ++j) {
      Eigen::Matrix3d w = block(i, j);
      for (int k = std::max(first, j - r_); k < j; ++k) w.noalias() -= work_[k - first] * block(j, k).transpose();
      work_[j - first] = w;
      Eigen::Matrix3d l = w.transpose();
      for (int c = 0; c < 3; ++c) solvePivot(block(j, j), reciprocals_[j], l.col(c));
      block(i, j) = l.transpose();
    }
    // D_i = A_ii − Σ_k W_ik L_ikᵀ: only the lower triangle of A_ii was assembled.
    Eigen::Matrix3d d = block(i, i).triangularView<Eigen::Lower>();
    d.triangularView<Eigen::StrictlyUpper>() = d.triangularView<Eigen::StrictlyLower>().transpose();
    for (int k = first; k < i; ++k) d.noalias() -= work_[k - first] * block(i, k).transpose();
    if (!factorPivot(d))
      return "zero or non-finite pivot in the 3x3 block of control point " + std::to_string(i) + " of " +
             std::to_string(n_);
    block(i, i) = d;
    reciprocals_[i] = d.diagonal().cwiseInverse();
  }
  return "";
}

void BlockBandLdlt::solve(Eigen::Ref<VecX> x) const {
  // L y = x, z = D⁻¹ y, Lᵀ x = z: block column i of Lᵀ is block row i of L, applied from the
  // last row up.
  for (int i = 1; i < n_; ++i) {
    Eigen::Vector3d sum = x.segment<3>(3 * i);
    for (int j = std::max(0, i - r_); j < i; ++j) sum.noalias() -= block(i, j) * x.segment<3>(3 * j);
    x.segment<3>(3 * i) = sum;
  }
  for (int i = 0; i < n_; ++i) solvePivot(block(i, i), reciprocals_[i], x.segment<3>(3 * i));
  for (int i = n_ - 1; i > 0; --i) {
    const Eigen::Vector3d xi = x.segment<3>(3 * i);
    for (int j = std::max(0, i - r_); j < i; ++j) x.segment<3>(3 * j).noalias() -= block(i, j).transpose() * xi;
  }
}

MatX BlockBandLdlt::reconstruct() const {
  MatX L = MatX::Identity(3 * n_, 3 * n_), D = MatX::Zero(3 * n_, 3 * n_);
  for (int i = 0; i < n_; ++i) {
    for (int j = std::max(0, i - r_); j < i; ++j) L.block<3, 3>(3 * i, 3 * j) = block(i, j);
    const Eigen::Matrix3d& f = block(i, i);
    Eigen::Matrix3d l = Eigen::Matrix3d::Identity();
    l(1, 0) = f(1, 0);
    l(2, 0) = f(2, 0);
    l(2, 1) = f(2, 1);
    D.block<3, 3>(3 * i, 3 * i) = l * f.diagonal().asDiagonal() * l.transpose();
  }
  return L * D * L.transpose();
}

}  // namespace filum::mechanics
