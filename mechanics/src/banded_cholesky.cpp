#include "filum/mechanics/banded_cholesky.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace filum::mechanics {

BandedCholesky::BandedCholesky(const SparseMatrix& matrix, int half_bandwidth)
    : n_(static_cast<int>(matrix.rows())), p_(half_bandwidth), band_(n_, half_bandwidth + 1) {
  band_.setZero();
  for (int i = 0; i < n_; ++i)
    for (SparseMatrix::InnerIterator it(matrix, i); it; ++it) {
      const int j = static_cast<int>(it.col());
      if (j > i) continue;
      if (i - j > p_) throw std::runtime_error("BandedCholesky: entry outside the declared band");
      at(i, j) = it.value();
    }
  // Cholesky–Banachiewicz restricted to the band: l_ij = (a_ij − Σ_k l_ik l_jk) / l_jj.
  for (int i = 0; i < n_; ++i) {
    for (int j = std::max(0, i - p_); j <= i; ++j) {
      double sum = at(i, j);
      for (int k = std::max(0, i - p_); k < j; ++k) sum -= at(i, k) * at(j, k);
      if (j < i) {
        at(i, j) = sum / at(j, j);
      } else {
        if (!(sum > 0.0))
          throw std::runtime_error("BandedCholesky: matrix is not positive definite (pivot " +
                                   std::to_string(i) + " = " + std::to_string(sum) + ")");
        at(i, i) = std::sqrt(sum);
      }
    }
  }
}

void BandedCholesky::solve(PointsRef B) const {
  // Forward substitution L Y = B, then back substitution Lᵀ X = Y, three columns at once.
  for (int i = 0; i < n_; ++i) {
    Eigen::RowVector3d r = B.row(i);
    for (int k = std::max(0, i - p_); k < i; ++k) r -= at(i, k) * B.row(k);
    B.row(i) = r / at(i, i);
  }
  for (int i = n_ - 1; i >= 0; --i) {
    Eigen::RowVector3d r = B.row(i);
    for (int k = i + 1; k <= std::min(n_ - 1, i + p_); ++k) r -= at(k, i) * B.row(k);
    B.row(i) = r / at(i, i);
  }
}

}  // namespace filum::mechanics
