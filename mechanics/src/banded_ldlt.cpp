#include "filum/mechanics/banded_ldlt.hpp"

#include <algorithm>
#include <cmath>

namespace filum::mechanics {

void BandedLdlt::resize(int n, int half_bandwidth) {
  n_ = n;
  p_ = std::max(0, std::min(half_bandwidth, n - 1));
  band_.setZero(n_, p_ + 1);
  work_.setZero(p_ + 1);
}

std::string BandedLdlt::factor() {
  // Row by row (Doolittle form of LDLᵀ restricted to the band), for j < i:
  //   l_ij = (a_ij − Σ_{k<j} l_ik d_k l_jk) / d_j,   d_i = a_ii − Σ_{k<i} l_ik d_k l_ik,
  // k running over the band only: O(n p²). Row i of the storage holds a_(i, i−p .. i)
  // contiguously, so each sum is a dot product of contiguous segments (Eigen vectorizes it).
  const int width = p_ + 1;
  double* band = band_.data();
  for (int i = 0; i < n_; ++i) {
    const int first = std::max(0, i - p_);
    double* row_i = band + static_cast<std::ptrdiff_t>(i) * width + (first - i + p_);  // a_(i, first)
    for (int j = first; j < i; ++j) {
      const int k0 = std::max(first, j - p_);
      const double* row_j = band + static_cast<std::ptrdiff_t>(j) * width + (k0 - j + p_);  // l_(j, k0)
      const int count = j - k0;
      double sum = row_i[j - first];
      if (count > 0)
        sum -= Eigen::Map<const VecX>(work_.data() + (k0 - first), count).dot(Eigen::Map<const VecX>(row_j, count));
      work_[j - first] = sum;  // l_ij d_j
      row_i[j - first] = sum / at(j, j);
    }
    const int count = i - first;
    double d = row_i[count];
    if (count > 0) d -= Eigen::Map<const VecX>(work_.data(), count).dot(Eigen::Map<const VecX>(row_i, count));
    if (!(std::abs(d) > 0.0) || !std::isfinite(d))
      return "zero or non-finite pivot " + std::to_string(d) + " at row " + std::to_string(i) + " of " +
             std::to_string(n_);
    row_i[count] = d;
  }
  return "";
}

MatX BandedLdlt::reconstruct() const {
  MatX L = MatX::Identity(n_, n_);
  VecX d(n_);
  for (int i = 0; i < n_; ++i) {
    for (int j = std::max(0, i - p_); j < i; ++j) L(i, j) = at(i, j);
    d[i] = at(i, i);
  }
  return L * d.asDiagonal() * L.transpose();
}

void BandedLdlt::solve(Eigen::Ref<VecX> x) const {
  // L y = x (row i of L is contiguous: a dot product), z = D⁻¹ y, Lᵀ x = z (column i of Lᵀ is
  // row i of L: an axpy, from the last row up).
  const int width = p_ + 1;
  const double* band = band_.data();
  for (int i = 0; i < n_; ++i) {
    const int first = std::max(0, i - p_), count = i - first;
    if (count > 0)
      x[i] -= Eigen::Map<const VecX>(band + static_cast<std::ptrdiff_t>(i) * width + (first - i + p_), count)
                  .dot(x.segment(first, count));
  }
  for (int i = 0; i < n_; ++i) x[i] /= at(i, i);
  for (int i = n_ - 1; i > 0; --i) {
    const int first = std::max(0, i - p_), count = i - first;
    x.segment(first, count) -=
        x[i] * Eigen::Map<const VecX>(band + static_cast<std::ptrdiff_t>(i) * width + (first - i + p_), count);
  }
}

}  // namespace filum::mechanics
