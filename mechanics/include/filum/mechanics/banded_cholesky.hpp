// BandedCholesky: M = L Lᵀ for a symmetric positive definite band matrix, factored once
// (precompute) and solved for the x, y and z columns together (solve) — the paper's O(n)
// resolution of M A = B (§3 "Real-time Simulation": bandwidth w = 2l − 1, 7 for cubic
// B-splines, so O(n w) per solve).
//
// Eigen has band storage but no band solver; SimplicialLLT on the sparse M is O(n) too but
// pays index indirection (apps/bench/bench_mass_solve compares both).
#pragma once

#include "filum/core/types.hpp"

namespace filum::mechanics {

class BandedCholesky {
 public:
  BandedCholesky() = default;
  /// Factors a symmetric matrix whose entries vanish beyond `half_bandwidth` off the diagonal.
  /// Throws std::runtime_error if it is not positive definite.
  BandedCholesky(const SparseMatrix& matrix, int half_bandwidth);

  /// In place B := M⁻¹ B, B is n × 3 (one column per coordinate).
  void solve(PointsRef B) const;

  int size() const { return n_; }
  int halfBandwidth() const { return p_; }

 private:
  // L stored by rows: l_(i, i−p+k) at band_(i, k), k = 0..p (k = p is the diagonal).
  double& at(int i, int j) { return band_(i, j - i + p_); }
  double at(int i, int j) const { return band_(i, j - i + p_); }

  int n_ = 0;
  int p_ = 0;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> band_;
};

}  // namespace filum::mechanics
