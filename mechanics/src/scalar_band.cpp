#include "filum/mechanics/scalar_band.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace filum::mechanics {

ScalarBand::ScalarBand(const SparseMatrix& matrix, int range)
    : n_(static_cast<int>(matrix.rows())), r_(std::max(0, range)), width_(2 * std::max(0, range) + 1) {
  values_.assign(static_cast<std::size_t>(n_) * width_, 0.0);
  for (int i = 0; i < matrix.outerSize(); ++i)
    for (SparseMatrix::InnerIterator it(matrix, i); it; ++it) {
      const int row = static_cast<int>(it.row()), col = static_cast<int>(it.col());
      if (std::abs(row - col) > r_) {
        if (it.value() == 0.0) continue;
        throw std::logic_error("ScalarBand: entry (" + std::to_string(row) + ", " + std::to_string(col) +
                               ") lies outside the half bandwidth " + std::to_string(r_));
      }
      values_[static_cast<std::size_t>(row) * width_ + (col - row + r_)] = it.value();
    }
}

namespace {

/// Rows [r, n − r) of out (±)= A x for a band of half width R known at compile time: each row is
/// the fixed-size product of its 2R + 1 values with the 2R + 1 rows of x around it (unrolled and
/// vectorized; the cubic spline's band is R = 3).
template <int R, bool kSubtract>
void applyInterior(const double* values, int n, ConstPointsRef x, PointsRef out) {
  constexpr int kWidth = 2 * R + 1;
  for (int i = R; i < n - R; ++i) {
    const Eigen::Map<const Eigen::Matrix<double, 1, kWidth>> row(values + static_cast<std::size_t>(i) * kWidth);
    const Eigen::Matrix<double, 1, 3> sum = row * x.middleRows<kWidth>(i - R);
    if (kSubtract)
      out.row(i) -= sum;
    else
      out.row(i) = sum;
  }
}

}  // namespace

template <bool kSubtract>
void ScalarBand::apply(ConstPointsRef x, PointsRef out) const {
  if (r_ == 3 && n_ > 2 * r_) {
    // Interior rows at full width (fixed size), then the r rows at each end below.
    applyInterior<3, kSubtract>(values_.data(), n_, x, out);
    applyRows<kSubtract>(0, r_, x, out);
    applyRows<kSubtract>(n_ - r_, n_, x, out);
    return;
  }
  applyRows<kSubtract>(0, n_, x, out);
}

template <bool kSubtract>
void ScalarBand::applyRows(int begin, int end, ConstPointsRef x, PointsRef out) const {
  for (int i = begin; i < end; ++i) {
    const int first = std::max(0, i - r_), last = std::min(n_ - 1, i + r_);
    const double* row = values_.data() + static_cast<std::size_t>(i) * width_ + (first - i + r_);
    double sum[3] = {0.0, 0.0, 0.0};
    for (int j = first; j <= last; ++j, ++row)
      for (int c = 0; c < 3; ++c) sum[c] += *row * x(j, c);
    for (int c = 0; c < 3; ++c) {
      if (kSubtract)
        out(i, c) -= sum[c];
      else
        out(i, c) = sum[c];
    }
  }
}

void ScalarBand::multiply(ConstPointsRef x, PointsRef out) const { apply<false>(x, out); }

void ScalarBand::subtractProduct(ConstPointsRef x, PointsRef out) const { apply<true>(x, out); }

}  // namespace filum::mechanics
