#include "filum/mechanics/block_band_ldlt.hpp"

#include <algorithm>
#include <cmath>

#include "filum/core/growing_vector.hpp"

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
  // One column of solveColumns: the same sweeps, the same operations in the same order.
  Eigen::Map<MatX> column(x.data(), x.size(), 1);
  solveColumns(column, 0);
}

void BlockBandLdlt::solveColumns(Eigen::Ref<MatX> x, int first) const {
  // L y = x, z = D⁻¹ y, Lᵀ x = z, with the loop over the columns inside the loop over the block
  // rows (the factors read once per block row for all the columns). Both sweeps gather: row i of
  // the forward sweep reads the y_j above it, y_i = x_i − Σ_{j<i} L_ij y_j; row i of the backward
  // sweep reads the x_k below it,
  //   x_i = D_i⁻¹ y_i − Σ_{k=i+1}^{i+r} L_kiᵀ x_k,
  // each sum kept in registers (a scatter, x_j −= L_ijᵀ x_i from each row i, would store and
  // reload x_j r times, one dependent store-to-load per block), and D_i⁻¹ applied on the way.
  // The sweeps are sequential (row i needs row i ∓ 1): the terms of the farther rows are summed
  // first, so that only the nearest block's product waits for the row just solved.
  // Columns go four at a time (kColumnChunk): each block is loaded once for the four, and their
  // four sums are independent chains where one column's is a chain of dependent subtractions. The
  // arithmetic of each column is the same in a chunk as alone, term by term and in the same order
  // (no contraction into fused multiply-adds: -ffp-contract=off), so a column's result does not
  // depend on the columns solved beside it (solve() is one column of this).
  // Rows before `first` are zero in every column and stay zero in the forward sweep
  // (y_i = x_i − Σ L_ij y_j = 0); row `first` has no non-zero term above it.
  const Eigen::Index columns = x.cols();
  first = std::clamp(first, 0, std::max(n_ - 1, 0));
  Eigen::Index k = 0;
  for (; k + kColumnChunk <= columns; k += kColumnChunk) sweepColumns<kColumnChunk>(x, k, first);
  for (; k < columns; ++k) sweepColumns<1>(x, k, first);
}

template <int Width>
void BlockBandLdlt::sweepColumns(Eigen::Ref<MatX>& x, Eigen::Index column, int first) const {
  const Eigen::Index stride = x.outerStride();
  double* v[Width];
  for (int c = 0; c < Width; ++c) v[c] = x.data() + (column + c) * stride;
  double s[Width][3];  // block row i of each column, summed in registers
  const auto store = [&](int i) {
    for (int c = 0; c < Width; ++c)
      for (int a = 0; a < 3; ++a) v[c][3 * i + a] = s[c][a];
  };
  for (int i = first + 1; i < n_; ++i) {
    const int j0 = std::max(first, i - r_);
    for (int c = 0; c < Width; ++c)
      for (int a = 0; a < 3; ++a) s[c][a] = v[c][3 * i + a];
    for (int j = j0; j < i; ++j) {
      const double* b = block(i, j).data();
      for (int c = 0; c < Width; ++c) {
        const double y0 = v[c][3 * j], y1 = v[c][3 * j + 1], y2 = v[c][3 * j + 2];
        s[c][0] -= b[0] * y0 + b[3] * y1 + b[6] * y2;
        s[c][1] -= b[1] * y0 + b[4] * y1 + b[7] * y2;
        s[c][2] -= b[2] * y0 + b[5] * y1 + b[8] * y2;
      }
    }
    store(i);
  }
  for (int i = n_ - 1; i >= 0; --i) {
    const int k1 = std::min(n_ - 1, i + r_);
    for (int c = 0; c < Width; ++c) {
      Eigen::Vector3d xi(v[c][3 * i], v[c][3 * i + 1], v[c][3 * i + 2]);
      solvePivot(block(i, i), reciprocals_[i], xi);
      s[c][0] = xi[0];
      s[c][1] = xi[1];
      s[c][2] = xi[2];
    }
    for (int k = k1; k > i; --k) {
      const double* b = block(k, i).data();
      for (int c = 0; c < Width; ++c) {
        const double y0 = v[c][3 * k], y1 = v[c][3 * k + 1], y2 = v[c][3 * k + 2];
        s[c][0] -= b[0] * y0 + b[1] * y1 + b[2] * y2;
        s[c][1] -= b[3] * y0 + b[4] * y1 + b[5] * y2;
        s[c][2] -= b[6] * y0 + b[7] * y1 + b[8] * y2;
      }
    }
    store(i);
  }
}

void BlockBandLdlt::inverseBand(std::vector<Eigen::Matrix3d>& z, int range) const {
  // Takahashi's equations (K. Takahashi, J. Fagan, M.-S. Chin, "Formation of a sparse bus
  // impedance matrix and its application to short circuit study", 8th PICA Conf. 1973; Erisman &
  // Tinney, CACM 18 (1975) 177): A = L D Lᵀ gives Lᵀ Z = D⁻¹ L⁻¹ for Z = A⁻¹, whose right side is
  // block lower triangular with D_i⁻¹ on its diagonal, so for i <= j
  //   Z_ij = δ_ij D_i⁻¹ − Σ_{k=i+1}^{i+r} L_kiᵀ Z_kj,
  // block rows from the last up, each from its farthest block to its diagonal. For the blocks
  // within a range R >= r (|i − j| <= R) every Z_kj read is within it too: k − j <= r <= R, and
  // j − k < j − i <= R; so a wider band costs O(n R r) 3 × 3 products, nothing outside it formed.
  const int wide = std::max(range, r_);
  const int width = wide + 1;
  resizeGrowing(z, static_cast<std::size_t>(n_) * width);  // (a steady caller allocates nothing)
  auto at = [&](int I, int J) -> Eigen::Matrix3d& { return z[static_cast<std::size_t>(I) * width + (J - I + wide)]; };
  for (int i = n_ - 1; i >= 0; --i) {
    const int last = std::min(n_ - 1, i + r_);       // the factor's blocks L_ki below row i
    const int farthest = std::min(n_ - 1, i + wide);  // the inverse's blocks Z_ij asked for
    for (int j = farthest; j >= i; --j) {
      Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
      if (j == i) {
        // D_i⁻¹ column by column (D_i as its own LDLᵀ: solvePivot).
        sum.setIdentity();
        for (int c = 0; c < 3; ++c) solvePivot(block(i, i), reciprocals_[i], sum.col(c));
      }
      for (int k = i + 1; k <= last; ++k) {
        // Z_kj: stored as (k, j) when k >= j, else as the transpose of (j, k).
        if (k >= j)
          sum.noalias() -= block(k, i).transpose() * at(k, j);
        else
          sum.noalias() -= block(k, i).transpose() * at(j, k).transpose();
      }
      at(j, i) = sum.transpose();  // Z_ji = Z_ijᵀ, the lower triangle's block
    }
  }
  // (Z_ii is symmetric up to round-off; its stored lower triangle is the one read.)
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
