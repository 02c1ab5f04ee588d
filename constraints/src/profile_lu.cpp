#include "filum/constraints/profile_lu.hpp"

#include <algorithm>
#include <cmath>

#include "filum/core/growing_vector.hpp"

namespace filum::constraints {

void ProfileLu::reset(int n) {
  n_ = n;
  resizeGrowing(first_, n);
  for (int i = 0; i < n; ++i) first_[i] = i;
}

void ProfileLu::allocate() {
  resizeGrowing(start_, n_ + 1);
  std::size_t total = 0;
  for (int i = 0; i < n_; ++i) {
    start_[i] = static_cast<int>(total);
    total += i - first_[i];
  }
  start_[n_] = static_cast<int>(total);
  resizeGrowing(lower_, total);
  resizeGrowing(upper_, total);
  resizeGrowing(diagonal_, n_);
  resizeGrowing(inverse_pivot_, n_);
  std::fill(lower_.begin(), lower_.end(), 0.0);
  std::fill(upper_.begin(), upper_.end(), 0.0);
  std::fill(diagonal_.begin(), diagonal_.end(), 0.0);
}

double ProfileLu::cost() const {
  double sum = 0.0;
  for (int i = 0; i < n_; ++i) sum += static_cast<double>(i - first_[i]) * (i - first_[i]);
  return sum;
}

bool ProfileLu::factor(bool positive_pivots) {
  for (int i = 0; i < n_; ++i) {
    const int fi = first_[i];
    double* l_row = lower_.data() + start_[i];  // L_ik at l_row[k − fi]
    double* u_col = upper_.data() + start_[i];  // U_ki at u_col[k − fi]
    for (int j = fi; j < i; ++j) {
      const int fj = first_[j], k0 = std::max(fi, fj);
      const double* l_row_j = lower_.data() + start_[j];
      const double* u_col_j = upper_.data() + start_[j];
      // Σ_k L_ik U_kj and Σ_k L_jk U_ki over their common envelope, two partial sums each: four
      // independent chains of multiply-adds instead of two (the short dot products, ~10 terms,
      // are bound by the adds' latency, not their throughput).
      const double* a = l_row + (k0 - fi);
      const double* b = u_col_j + (k0 - fj);
      const double* c = l_row_j + (k0 - fj);
      const double* d = u_col + (k0 - fi);
      const int length = j - k0;
      double sum_l0 = 0.0, sum_l1 = 0.0, sum_u0 = 0.0, sum_u1 = 0.0;
      int k = 0;
      for (; k + 1 < length; k += 2) {
        sum_l0 += a[k] * b[k];
        sum_u0 += c[k] * d[k];
        sum_l1 += a[k + 1] * b[k + 1];
        sum_u1 += c[k + 1] * d[k + 1];
      }
      if (k < length) {
        sum_l0 += a[k] * b[k];
        sum_u0 += c[k] * d[k];
      }
      l_row[j - fi] = (l_row[j - fi] - (sum_l0 + sum_l1)) * inverse_pivot_[j];
      u_col[j - fi] -= sum_u0 + sum_u1;
    }
    double pivot = diagonal_[i];
    for (int k = fi; k < i; ++k) pivot -= l_row[k - fi] * u_col[k - fi];
    // (A subnormal pivot passes the first two tests but has no finite reciprocal: refused too.)
    if (!(std::abs(pivot) > 0.0) || !std::isfinite(pivot) || !std::isfinite(1.0 / pivot) ||
        (positive_pivots && !(pivot > 0.0)))
      return false;
    diagonal_[i] = pivot;
    inverse_pivot_[i] = 1.0 / pivot;
  }
  return true;
}

void ProfileLu::solve(Eigen::Ref<VecX> x) const {
  // L y = x (unit lower, by rows), then U x = y (by columns, from the last).
  for (int i = 0; i < n_; ++i) {
    // Two partial sums, as in factor(): two chains of multiply-adds.
    const double* l_row = lower_.data() + start_[i];
    const double* xk = x.data() + first_[i];
    const int length = i - first_[i];
    double sum0 = 0.0, sum1 = 0.0;
    int k = 0;
    for (; k + 1 < length; k += 2) {
      sum0 += l_row[k] * xk[k];
      sum1 += l_row[k + 1] * xk[k + 1];
    }
    if (k < length) sum0 += l_row[k] * xk[k];
    x[i] -= sum0 + sum1;
  }
  for (int i = n_ - 1; i >= 0; --i) {
    x[i] *= inverse_pivot_[i];
    const double* u_col = upper_.data() + start_[i];
    for (int k = first_[i]; k < i; ++k) x[k] -= u_col[k - first_[i]] * x[i];
  }
}

}  // namespace filum::constraints
