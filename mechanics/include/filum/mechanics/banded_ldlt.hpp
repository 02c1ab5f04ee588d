// BandedLdlt: A = L D Lᵀ for a symmetric band matrix that need not be positive definite — the
// matrix of an implicit step, A = M − θh D − κh² K (DESIGN.md "Numbers that matter"), over one
// spline's 3n coordinates interleaved x0 y0 z0 x1 ... For a spline of degree d, control points
// i and j interact only when |i − j| <= d, so the half bandwidth is 3d + 2 (11 for the cubic
// B-spline) and factor + solve cost O(n d²): the 3n × 3n generalisation of BandedCholesky.
//
// No pivoting: A is symmetric and, for the step sizes an implicit scheme takes, dominated by the
// positive definite M; a stiffness with negative eigenvalues (a compressed thread) makes A
// indefinite but LDLᵀ still goes through unless a pivot vanishes, which factor() reports.
//
// Storage is allocated by resize() and reused: assembling and factoring a new matrix of the same
// size allocates nothing.
#pragma once

#include <string>

#include "filum/core/types.hpp"

namespace filum::mechanics {

class BandedLdlt {
 public:
  /// n × n matrix with entries only for |i − j| <= half_bandwidth; sets it to zero.
  void resize(int n, int half_bandwidth);
  /// Zeroes the matrix (keeps the size and the storage).
  void setZero() { band_.setZero(); }
  /// Copies the entries of another unfactored matrix of the same size and bandwidth.
  void assign(const BandedLdlt& other) { band_ = other.band_; }
  /// a_ij += value for i >= j (the lower triangle; the matrix is symmetric).
  /// Precondition: i − j <= halfBandwidth().
  void addLower(int i, int j, double value) { band_(i, j - i + p_) += value; }

  /// Factors in place. Returns "" on success, else why it failed (a zero or non-finite pivot).
  std::string factor();
  /// In place x := A⁻¹ x (after factor()).
  void solve(Eigen::Ref<VecX> x) const;
  /// The dense matrix L D Lᵀ of the factors (after factor(); for tests and diagnostics).
  MatX reconstruct() const;

  int size() const { return n_; }
  int halfBandwidth() const { return p_; }

 private:
  // Row i holds a_(i, i−p .. i) at band_(i, 0 .. p); after factor(), the strictly lower part
  // holds L (unit diagonal implied) and the diagonal column p holds D.
  double at(int i, int j) const { return band_(i, j - i + p_); }
  double& at(int i, int j) { return band_(i, j - i + p_); }

  int n_ = 0;
  int p_ = 0;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> band_;
  VecX work_;  // l_ik d_k of the row being factored (p values)
};

}  // namespace filum::mechanics
