#include "filum/mechanics/block_band_matrix.hpp"

#include <algorithm>
#include <cstdlib>

namespace filum::mechanics {

void BlockBandMatrix::resize(int first_point, int points, int range) {
  first_ = first_point;
  n_ = std::max(0, points);
  r_ = std::max(0, std::min(range, n_ - 1));
  width_ = 2 * r_ + 1;
  blocks_.assign(static_cast<std::size_t>(n_) * width_, Eigen::Matrix3d::Zero());
  misfits_ = 0;
  needed_range_ = 0;
}

void BlockBandMatrix::setZero() {
  for (Eigen::Matrix3d& b : blocks_) b.setZero();
  misfits_ = 0;
  needed_range_ = 0;
}

bool BlockBandMatrix::fits(int i, int j) {
  const int li = i - first_, lj = j - first_;
  const bool inside = li >= 0 && li < n_ && lj >= 0 && lj < n_;
  const int distance = std::abs(li - lj);
  if (inside) needed_range_ = std::max(needed_range_, distance);
  if (inside && distance <= r_) return true;
  ++misfits_;
  return false;
}

void BlockBandMatrix::addBlock(int i, int j, const Eigen::Matrix3d& value) {
  if (fits(i, j)) block(i - first_, j - first_) += value;
}

void BlockBandMatrix::addEntry(int row, int col, double value) {
  const int i = row / 3, j = col / 3;
  if (fits(i, j)) block(i - first_, j - first_)(row % 3, col % 3) += value;
}

void BlockBandMatrix::addIsotropic(int i, int j, double value) {
  if (fits(i, j)) block(i - first_, j - first_).diagonal().array() += value;
}

void BlockBandMatrix::addSupportBlocks(int first, int count, const Eigen::Matrix3d* lower) {
  if (count <= 0) return;
  // Both ends inside and count − 1 <= r: every pair of the support is stored.
  const int li = first - first_;
  if (li < 0 || li + count > n_ || count - 1 > r_) {
    JacobianAccumulator::addSupportBlocks(first, count, lower);  // block by block, misfits counted
    return;
  }
  needed_range_ = std::max(needed_range_, count - 1);
  for (int a = 0, k = 0; a < count; ++a) {
    for (int b = 0; b < a; ++b, ++k) {  // pair (a, b) at k = a (a + 1) / 2 + b, diagonal last
      block(li + a, li + b) += lower[k];
      block(li + b, li + a) += lower[k].transpose();
    }
    block(li + a, li + a) += lower[k++];
  }
}

void BlockBandMatrix::multiplyAdd(Eigen::Ref<const VecX> x, double factor, Eigen::Ref<VecX> y) const {
  // y_i += factor Σ_j A_ij x_j over the band.
  for (int i = 0; i < n_; ++i) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    const int last = std::min(n_ - 1, i + r_);
    for (int j = std::max(0, i - r_); j <= last; ++j) sum.noalias() += block(i, j) * x.segment<3>(3 * j);
    y.segment<3>(3 * i) += factor * sum;
  }
}

void BlockBandMatrix::addSymmetrizedTo(double factor, JacobianAccumulator& out) const {
  for (int i = 0; i < n_; ++i) {
    const Eigen::Matrix3d& d = block(i, i);
    out.addBlock(first_ + i, first_ + i, (0.5 * factor) * (d + d.transpose()));
    for (int j = std::max(0, i - r_); j < i; ++j)
      out.addBlockPair(first_ + i, first_ + j, (0.5 * factor) * (block(i, j) + block(j, i).transpose()));
  }
}

}  // namespace filum::mechanics
