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
  // k running over the band only: O(n p²).
  for (int i = 0; i < n_; ++i) {
    const int first = std::max(0, i - p_);
    for (int j = first; j < i; ++j) {
      double sum = at(i, j);
      for (int k = std::max(first, j - p_); k < j; ++k) sum -= work_[k - first] * at(j, k);
      work_[j - first] = sum;  // l_ij d_j
      at(i, j) = sum / at(j, j);
    }
    double d = at(i, i);
    for (int k = first; k < i; ++k) d -= work_[k - first] * at(i, k);
    if (!(std::abs(d) > 0.0) || !std::isfinite(d))
      return "zero or non-finite pivot " + std::to_string(d) + " at row " + std::to_string(i) + " of " +
             std::to_string(n_);
    at(i, i) = d;
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
  // L y = x, z = D⁻¹ y, Lᵀ x = z.
  for (int i = 0; i < n_; ++i) {
    double sum = x[i];
    for (int k = std::max(0, i - p_); k < i; ++k) sum -= at(i, k) * x[k];
    x[i] = sum;
  }
  for (int i = 0; i < n_; ++i) x[i] /= at(i, i);
  for (int i = n_ - 1; i >= 0; --i) {
    double sum = x[i];
    for (int k = i + 1; k <= std::min(n_ - 1, i + p_); ++k) sum -= at(k, i) * x[k];
    x[i] = sum;
  }
}

}  // namespace filum::mechanics
