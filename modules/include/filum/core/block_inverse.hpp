// BlockInverse: applies the inverse of a block-diagonal system matrix, one block per body —
// the mass matrix M for explicit steps (A = M⁻¹B, paper eq. 3), or the matrix of an implicit
// step (M − h D − h² K). Constraint solvers work through it, so the acceleration decomposition
// of paper §4 serves explicit and implicit integrators alike.
#pragma once

#include <stdexcept>
#include <vector>

#include "filum/core/types.hpp"

namespace filum {

/// One body's block of a BlockInverse's matrix A as a band of 3 × 3 blocks: a view into the
/// matrix's own storage, for a solver that factors A together with constraint rows instead of
/// forming W = L A⁻¹ Lᵀ (ContactNewton's structured step).
struct BandBlocks {
  int groups = 0;  // block rows: the body's points and internal triples, in the band's order
  int range = 0;   // block (I, J) may be non-zero for |I − J| <= range
  const Eigen::Matrix3d* lower = nullptr;  // blocks (I, I − range .. I), row by row
  const int* point_group = nullptr;        // the block row of each of the body's points
  /// Block (I, J), I >= J >= I − range (A is symmetric: (J, I) is its transpose).
  const Eigen::Matrix3d& block(int I, int J) const { return lower[I * (range + 1) + (J - I + range)]; }
};

class BlockInverse {
 public:
  virtual ~BlockInverse() = default;
  /// In place x := A_b⁻¹ x for body b's block x (3 n_b values, x0 y0 z0 x1 ...).
  /// Only valid when !coupled().
  virtual void solveBlock(int body, Eigen::Ref<VecX> x) const = 0;
  /// In place X := A_b⁻¹ X for several right-hand sides at once, one per column of X (3 n_b rows
  /// each), whose points before `first_point` (of the body) are zero in every column. The
  /// default solves the columns one by one; an operator whose factors are cheaper to sweep once
  /// for several columns (a band: each block read once, the columns' sweeps independent) does
  /// better. The result is the same, bit for bit, as solveBlock's on each column.
  virtual void solveBlockColumns(int body, Eigen::Ref<MatX> x, int /*first_point*/) const {
    for (Eigen::Index k = 0; k < x.cols(); ++k) solveBlock(body, x.col(k));
  }

  /// True when the matrix couples bodies (e.g. an implicit step with a force between two
  /// bodies): it is then not block diagonal, and solves must use solveAll on whole vectors.
  virtual bool coupled() const { return false; }
  /// In place x := A⁻¹ x for a whole-scene vector (3N). Needed only when coupled().
  virtual void solveAll(Eigen::Ref<VecX> /*x*/) const {
    throw std::logic_error("BlockInverse::solveAll is not implemented by a block-diagonal inverse");
  }

  /// a (velocity layout) += the bodies' internal DOFs' response to forces f on the points (3N):
  /// their part of A⁻¹ [f; 0]. Nothing where A does not couple internal DOFs to points (the mass
  /// matrix); an implicit step's matrix does for a rod (its frames turn with its points), and a
  /// constraint solver calls this after scattering Lᵀλ so that the frames follow the constraint.
  virtual void addInternalResponse(Eigen::Ref<const VecX> /*point_forces*/, VecX& /*a*/) const {}

  /// True when every block is I₃ ⊗ A_b: the same n_b × n_b matrix on x, y and z, as the mass
  /// matrix is (paper eq. 3). A constraint solver may then solve three scalar right-hand sides
  /// with one solveBlock (one per coordinate column) and share A_b⁻¹ b(s) between the rows of
  /// a constraint (a fixed point's 3 rows need one scalar solve, not three 3-column ones).
  /// Implicit step matrices M − h D − h² K mix the coordinates: false (the safe default).
  virtual bool sameOnEveryAxis() const { return false; }
  /// A number that changes whenever the matrix changes, so that a solver may keep A⁻¹Lᵀ from
  /// one call to the next for rows that did not change; −1 (the default): it may change at
  /// any call, keep nothing. The mass matrix never changes: 0.
  virtual long revision() const { return -1; }

  /// Body b's block of A as a band (A itself, not its factors), valid until A changes; false when
  /// A is not held so: the mass operator, sparse or coupled blocks, rank-one terms (the default).
  virtual bool bandBlocks(int /*body*/, BandBlocks& /*out*/) const { return false; }
  /// Body b's blocks of A⁻¹ within R = max(range, its band's range) block diagonals, in
  /// bandBlocks' order (row I holding (A⁻¹)_{I, I − R .. I}, R + 1 blocks a row), into `out` (grown,
  /// never shrunk): W's entries between points R groups apart without a solve per row. False when
  /// the body has no band factor (then bandBlocks is false too).
  virtual bool inverseBandBlocks(int /*body*/, int /*range*/, std::vector<Eigen::Matrix3d>& /*out*/) const {
    return false;
  }
};

}  // namespace filum
