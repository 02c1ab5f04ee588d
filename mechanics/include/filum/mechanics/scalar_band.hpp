// ScalarBand: a constant symmetric n × n matrix with half bandwidth r (entries (i, j) with
// |i − j| <= r), stored densely by rows — the isotropic constant terms of a spline, the mass
// matrix M (paper eq. 3) and the parametric bending stiffness K_b, which act as A ⊗ I₃ on the
// n × 3 control points. Its product with the points is a fixed-stride loop over 2r + 1 diagonals:
//   (A X)_i = Σ_{j = max(0, i − r)}^{min(n − 1, i + r)} A_ij X_j   (X_j: row j of the n × 3 points),
// with no index arrays to follow (a compressed sparse product reads one per entry).
#pragma once

#include <vector>

#include "filum/core/types.hpp"

namespace filum::mechanics {

class ScalarBand {
 public:
  ScalarBand() = default;
  /// The entries of `matrix` (n × n) within half bandwidth `range`; entries further out must be
  /// zero (they are not stored).
  ScalarBand(const SparseMatrix& matrix, int range);

  int size() const { return n_; }
  int range() const { return r_; }
  /// A_ij for |i − j| <= range().
  double operator()(int i, int j) const { return values_[static_cast<std::size_t>(i) * width_ + (j - i + r_)]; }

  /// out = A X (n × 3 points).
  void multiply(ConstPointsRef x, PointsRef out) const;
  /// out −= A X.
  void subtractProduct(ConstPointsRef x, PointsRef out) const;

 private:
  template <bool kSubtract>
  void apply(ConstPointsRef x, PointsRef out) const;
  /// Rows [begin, end) of apply, row by row at their own width.
  template <bool kSubtract>
  void applyRows(int begin, int end, ConstPointsRef x, PointsRef out) const;

  int n_ = 0, r_ = 0, width_ = 1;
  std::vector<double> values_;  // row i: A_{i, i − r} .. A_{i, i + r} (zeros outside the matrix)
};

}  // namespace filum::mechanics
