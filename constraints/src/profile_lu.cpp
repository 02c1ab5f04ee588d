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
      double sum_l = 0.0, sum_u = 0.0;
      for (int k = k0; k < j; ++k) {
        sum_l += l_row[k - fi] * u_col_j[k - fj];
        sum_u += l_row_j[k - fj] * u_col[k - fi];
      }
      l_row[j - fi] = (l_row[j - fi] - sum_l) / diagonal_[j];
      u_col[j - fi] -= sum_u;
    }
    double pivot = diagonal_[i];
    for (int k = fi; k < i; ++k) pivot -= l_row[k - fi] * u_col[k - fi];
    if (!(std::abs(pivot) > 0.0) || !std::isfinite(pivot) || (positive_pivots && !(pivot > 0.0))) return false;
    diagonal_[i] = pivot;
  }
  return true;
}

void ProfileLu::solve(Eigen::Ref<VecX> x) const {
  // L y = x (unit lower, by rows), then U x = y (by columns, from the last).
  for (int i = 0; i < n_; ++i) {
    const double* l_row = lower_.data() + start_[i];
    double sum = x[i];
    for (int k = first_[i]; k < i; ++k) sum -= l_row[k - first_[i]] * x[k];
    x[i] = sum;
  }
  for (int i = n_ - 1; i >= 0; --i) {
    x[i] /= diagonal_[i];
    const double* u_col = upper_.data() + start_[i];
    for (int k = first_[i]; k < i; ++k) x[k] -= u_col[k - first_[i]] * x[i];
  }
}

}  // namespace filum::constraints
