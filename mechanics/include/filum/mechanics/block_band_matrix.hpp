// BlockBandMatrix: a matrix of one body's n × n blocks of 3 × 3 whose block (i, j) is stored for
// |i − j| <= r (2r + 1 block diagonals, the whole band: no symmetry assumed), written through the
// JacobianAccumulator interface in the scene's global point numbering. It holds a force Jacobian
// that a force field needs as a matrix — RayleighDamping keeps K(q) of the elastic fields in one —
// so that the product K w and copying K into the step matrix cost O(n r) fixed-size 3 × 3
// operations, with no triplet list.
//
// An entry outside the band (|i − j| > r, or a point of another body) does not fit: it is
// counted in misfit(), with the range it needed; the owner resizes and fills again. Storage is
// allocated by resize() and reused by setZero().
#pragma once

#include <vector>

#include <Eigen/Core>

#include "filum/core/jacobian_accumulator.hpp"
#include "filum/core/types.hpp"

namespace filum::mechanics {

class BlockBandMatrix final : public JacobianAccumulator {
 public:
  /// Points [first_point, first_point + points) of the global numbering, block range r >= 0;
  /// all blocks zero.
  void resize(int first_point, int points, int range);
  void setZero();

  int firstPoint() const { return first_; }
  int points() const { return n_; }
  int range() const { return r_; }
  /// Entries added since setZero() that did not fit; the largest |i − j| any entry needed.
  int misfits() const { return misfits_; }
  int neededRange() const { return needed_range_; }

  /// Block (i, j) in local point indices, |i − j| <= range().
  Eigen::Matrix3d& block(int i, int j) { return blocks_[static_cast<std::size_t>(i) * width_ + (j - i + r_)]; }
  const Eigen::Matrix3d& block(int i, int j) const {
    return blocks_[static_cast<std::size_t>(i) * width_ + (j - i + r_)];
  }

  /// y += factor · A x on this body's coordinates (x, y: 3n values, x0 y0 z0 x1 ...).
  void multiplyAdd(Eigen::Ref<const VecX> x, double factor, Eigen::Ref<VecX> y) const;
  /// out += factor · (A + Aᵀ)/2 in global points: the diagonal blocks, and each off-diagonal pair
  /// once (JacobianAccumulator::addBlockPair). A symmetric A is copied as it is.
  void addSymmetrizedTo(double factor, JacobianAccumulator& out) const;

  // JacobianAccumulator, global points.
  void addBlock(int i, int j, const Eigen::Matrix3d& value) override;
  void addEntry(int row, int col, double value) override;
  void addIsotropic(int i, int j, double value) override;
  /// One layout check for the whole support (both ends fit: every pair fits), then direct adds.
  void addSupportBlocks(int first, int count, const Eigen::Matrix3d* lower) override;

 private:
  /// True when global points i and j have a stored block; notes a misfit otherwise.
  bool fits(int i, int j);

  int first_ = 0, n_ = 0, r_ = 0, width_ = 1;
  int misfits_ = 0, needed_range_ = 0;
  std::vector<Eigen::Matrix3d> blocks_;  // row i: blocks (i, i − r .. i + r)
};

}  // namespace filum::mechanics
