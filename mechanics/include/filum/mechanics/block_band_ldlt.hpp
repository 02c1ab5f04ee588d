// BlockBandLdlt: A = L D Lᵀ by 3 × 3 blocks for the symmetric block-band matrix of an implicit
// step, A = M − θh D − κh² K over one spline's n control points (docs/architecture.md, "Numbers
// that matter").
// Control points i and j interact only when |i − j| <= r (r = d, the degree, for a spline), so A
// has 2r + 1 block diagonals; L is unit block lower triangular with the same band, D block
// diagonal (3 × 3 symmetric blocks). For block rows i, j < i:
//   W_ij = A_ij − Σ_{k<j} W_ik L_jkᵀ,   L_ij = W_ij D_j⁻¹,   D_i = A_ii − Σ_{k<i} W_ik L_ikᵀ,
// (W_ik = L_ik D_k), k over the band only: O(n r²) fixed-size 3 × 3 products, each D_j factored
// by its own scalar LDLᵀ. The arithmetic is that of a scalar band LDLᵀ of half bandwidth 3r + 2,
// but each step is a dozen independent multiply-adds instead of one long dependent dot product.
//
// No pivoting: A is symmetric and, for the step sizes an implicit scheme takes, dominated by the
// positive definite M; a stiffness with negative eigenvalues (a compressed thread) makes A
// indefinite; LDLᵀ still goes through unless a pivot vanishes, which factor() reports.
//
// The step matrix adds whole blocks (block()); addLower takes one scalar entry on interleaved
// coordinates 3i + axis. Storage is allocated by resize() and reused.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "filum/core/types.hpp"

namespace filum::mechanics {

class BlockBandLdlt {
 public:
  /// A matrix of `points` × `points` blocks of 3 × 3 (size 3 points) whose block (i, j) may be
  /// non-zero for |i − j| <= range; sets it to zero.
  void resize(int points, int range);
  void setZero();
  /// Copies the entries of another unfactored matrix of the same size and bandwidth.
  void assign(const BlockBandLdlt& other) { blocks_ = other.blocks_; }
  /// a_ij += value for i >= j (lower triangle, coordinates 3·point + axis), |i/3 − j/3| <= range.
  void addLower(int i, int j, double value) {
    block(i / 3, j / 3)(i % 3, j % 3) += value;
  }
  /// Block (I, J), I >= J, before factor(): J in [I − r, I].
  Eigen::Matrix3d& block(int I, int J) { return blocks_[static_cast<std::size_t>(I) * width_ + (J - I + r_)]; }
  const Eigen::Matrix3d& block(int I, int J) const { return blocks_[static_cast<std::size_t>(I) * width_ + (J - I + r_)]; }

  /// Factors in place. Returns "" on success, else why it failed (a singular or non-finite pivot).
  std::string factor();
  /// In place x := A⁻¹ x (after factor()).
  void solve(Eigen::Ref<VecX> x) const;
  /// In place X := A⁻¹ X for each column of X, whose block rows before `first` are zero (the
  /// forward sweep starts there). The same operations on each column as solve(): the same result
  /// bit for bit. Each block of the factors is read once per block row for four columns, and the
  /// four columns' dependent chains (row i waits for row i ∓ 1) overlap.
  void solveColumns(Eigen::Ref<MatX> x, int first = 0) const;
  /// The blocks of A⁻¹ within `range` block diagonals (after factor(); at least the band's r),
  /// row I holding (A⁻¹)_{I, I − R .. I} for R = max(range, r) (the blocks above the diagonal are
  /// their transposes; blocks() is the layout for R = r). O(n R r), by Takahashi's equations; for
  /// W's entries between rows a band apart without a solve per row.
  void inverseBand(std::vector<Eigen::Matrix3d>& z, int range) const;
  /// The dense matrix L D Lᵀ of the factors (after factor(); for tests and diagnostics).
  MatX reconstruct() const;

  int size() const { return 3 * n_; }
  int points() const { return n_; }
  int range() const { return r_; }
  /// The blocks, row I holding (I, I − r .. I) (before factor(): A's; after: the factors).
  const Eigen::Matrix3d* blocks() const { return blocks_.data(); }
  /// Scalar half bandwidth 3 r + 2.
  int halfBandwidth() const { return 3 * r_ + 2; }

 private:
  static constexpr int kColumnChunk = 4;  // columns swept together by solveColumns
  /// Both sweeps of solveColumns on columns [column, column + Width) of x.
  template <int Width>
  void sweepColumns(Eigen::Ref<MatX>& x, Eigen::Index column, int first) const;

  int n_ = 0;      // block rows
  int r_ = 0;      // block half bandwidth
  int width_ = 1;  // r + 1 blocks per row
  // Row I holds blocks (I, I − r .. I); after factor() the strictly lower ones are L, the
  // diagonal one D_I as its own LDLᵀ (δ on the diagonal, the unit lower factor below).
  std::vector<Eigen::Matrix3d> blocks_;
  std::vector<Eigen::Vector3d> reciprocals_;  // 1/δ of each D_I (after factor())
  std::vector<Eigen::Matrix3d> work_;  // W_Ik = L_Ik D_k of the row being factored (r + 1)
};

}  // namespace filum::mechanics
