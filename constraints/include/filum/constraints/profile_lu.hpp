// ProfileLu: K = L U without pivoting for a square matrix whose non-zeros lie in a symmetric
// envelope (profile, skyline): row i of the lower triangle and column i of the upper one run
// from column (row) first(i) to i. Elimination without pivoting creates fill only inside the
// envelope (George & Liu, "Computer Solution of Large Sparse Positive Definite Systems", 1981,
// §4.2), so the factors are stored in it: row i of L and column i of U as contiguous runs of
// i − first(i) values, the diagonal of U apart. The cost is Σ_i (i − first(i))² multiply-adds
// (two dot products per envelope entry), against n³/3 for a dense LU.
//
// Crout order (the envelope form of Doolittle's algorithm), for i = 0 .. n − 1 and
// j = first(i) .. i − 1, with k over max(first(i), first(j)) .. j − 1:
//   L_ij = (K_ij − Σ_k L_ik U_kj) / U_jj,     U_ji = K_ji − Σ_k L_jk U_ki,
//   U_ii = K_ii − Σ_{k = first(i)}^{i−1} L_ik U_ki.
// Both sums run over contiguous memory (a row of L, a column of U); the division is a product with
// 1/U_jj, formed once per pivot.
//
// Without pivoting the factorization needs pivots bounded away from zero relative to their rows.
// Symmetric quasi-definite matrices have an LDLᵀ factorization in any order (Vanderbei, SIAM J.
// Optim. 5 (1995) 100: existence, not a stability bound), and the caller orders its unknowns so
// that its pivots are of the size of its own diagonal (contact Newton: a constraint row after the
// points it acts on). factor() refuses a zero or non-finite pivot; the caller checks that the
// solution is finite (a huge finite one is left to its line search). Storage grows only:
// refactoring a matrix of a size and envelope seen before allocates nothing.
#pragma once

#include <cassert>
#include <vector>

#include "filum/core/types.hpp"

namespace filum::constraints {

class ProfileLu {
 public:
  /// Starts a matrix of order n with an empty envelope (the diagonal only).
  void reset(int n);
  /// Widens the envelope to hold entries (i, j) and (j, i).
  void widen(int i, int j) {
    const int lo = i < j ? i : j, hi = i < j ? j : i;
    if (lo < first_[hi]) first_[hi] = lo;
  }
  /// Lays the storage out for the envelope and sets every entry to zero; call after the widen()s.
  void allocate();
  /// Entry (i, j), which must lie in the envelope (after allocate(), before factor()).
  double& at(int i, int j) {
    assert((i < j ? i >= first_[j] : j >= first_[i]) && "ProfileLu::at outside the envelope");
    if (i == j) return diagonal_[i];
    if (i > j) return lower_[start_[i] + (j - first_[i])];
    return upper_[start_[j] + (i - first_[j])];
  }
  /// Factors in place; false (and the factors are unusable) on a zero or non-finite pivot.
  /// With positive_pivots, also on a pivot <= 0. For [A −Lᵀ; L 0] with A positive definite and
  /// independent rows, each placed after its points, every pivot is positive (A's Schur
  /// complements, then those of L A⁻¹ Lᵀ); a pivot <= 0 so shows an A that is not definite (or
  /// dependent rows) — the converse need not hold.
  bool factor(bool positive_pivots = false);
  /// x := K⁻¹ x after factor().
  void solve(Eigen::Ref<VecX> x) const;

  int size() const { return n_; }
  /// Σ_i (i − first(i))²: the factorization's multiply-adds, for choosing it over a dense LU.
  double cost() const;

 private:
  int n_ = 0;
  std::vector<int> first_, start_;
  std::vector<double> lower_, upper_, diagonal_;
  std::vector<double> inverse_pivot_;  // 1 / U_jj, set as each pivot is (factor)
};

}  // namespace filum::constraints
