// JacobianAccumulator: where the matrix of an implicit step, A = M − θh D − κh² K, is assembled
// (docs/architecture.md, "Numbers that matter"). Bodies add their mass, force fields their Jacobians
// k·K + d·D (ForceField::addJacobian), contact pipelines their penalty Jacobians, each straight
// into the structure the accumulator owns: the step matrix adds 3 × 3 blocks into one band per
// body (mechanics/step_matrix.hpp), with no triplet list, scatter or sort in the step.
//
// Coordinates are the scene's global 3N point coordinates (3·point + axis), points numbered as in
// the SceneState (MechanicalState::offset() + local index), and after them the bodies' internal
// DOFs in triples (a rod's frame rotations): group N + k for the k-th triple of the scene
// (MechanicalState::internalGroup), coordinate 3 (N + k) + axis — a numbering of the matrix
// only (in the SceneState the internal DOFs follow the extra DOFs). Every call adds; nothing is
// replaced.
// The matrices are symmetric or symmetrised by the consumer: A ← (A + Aᵀ)/2 (a dashpot's
// Jacobian is not exactly symmetric; Newton then converges a little slower, to the same answer).
//
// TripletAccumulator appends triplets instead: the reference assembly that the band assembly is
// tested against, and the input of eigen-analyses (apps/validation/stability.cpp).
#pragma once

#include "filum/core/types.hpp"

namespace filum {

class JacobianAccumulator {
 public:
  virtual ~JacobianAccumulator() = default;

  /// A(3i + r, 3j + c) += block(r, c) for global points i and j.
  virtual void addBlock(int i, int j, const Eigen::Matrix3d& block) = 0;

  /// A(3i..3i+2, 3j..3j+2) += block and A(3j.., 3i..) += blockᵀ (i ≠ j): one symmetric pair,
  /// added once by the caller.
  virtual void addBlockPair(int i, int j, const Eigen::Matrix3d& block) {
    addBlock(i, j, block);
    addBlock(j, i, block.transpose());
  }

  /// The symmetric blocks of a term over `count` consecutive points from global point `first`
  /// (a spline piece's support): lower[k] for the pair (a, b <= a) numbered k = a (a + 1) / 2 + b,
  /// added at (first + a, first + b) and, for a ≠ b, its transpose at (first + b, first + a).
  /// Diagonal blocks must be symmetric. One call per support lets the band step matrix check the
  /// layout once for all count (count + 1) / 2 blocks.
  virtual void addSupportBlocks(int first, int count, const Eigen::Matrix3d* lower) {
    for (int a = 0, k = 0; a < count; ++a)
      for (int b = 0; b <= a; ++b, ++k) {
        if (a == b)
          addBlock(first + a, first + a, lower[k]);
        else
          addBlockPair(first + a, first + b, lower[k]);
      }
  }

  /// A(row, col) += value for global coordinates row and col (3·point + axis).
  virtual void addEntry(int row, int col, double value) = 0;

  /// A(3i + r, 3j + r) += value for r = 0, 1, 2: the isotropic block value·I₃ of a term that is
  /// the same on every axis (M ⊗ I₃, paper eq. 3; parametric bending; viscous damping).
  virtual void addIsotropic(int i, int j, double value) = 0;

  /// A += factor · u uᵀ, u given over `u.rows()` consecutive points from global point `first`
  /// (u.rows() × 3): the rank-one part of a global energy (GlobalStretching's Ê''(l) ∇l ∇lᵀ).
  /// The band step matrix keeps it apart and solves with Sherman–Morrison; the default adds it
  /// entry by entry (dense).
  virtual void addRankOne(int first, ConstPointsRef u, double factor) {
    const int n = static_cast<int>(u.rows());
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) addBlock(first + i, first + j, factor * u.row(i).transpose() * u.row(j));
  }
};

/// Appends every entry as a triplet (global 3N coordinates), zeros of a block included, so that
/// the pattern does not depend on the values.
class TripletAccumulator final : public JacobianAccumulator {
 public:
  explicit TripletAccumulator(Triplets& out) : out_(out) {}
  void addBlock(int i, int j, const Eigen::Matrix3d& block) override {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out_.emplace_back(3 * i + r, 3 * j + c, block(r, c));
  }
  void addEntry(int row, int col, double value) override { out_.emplace_back(row, col, value); }
  void addIsotropic(int i, int j, double value) override {
    for (int r = 0; r < 3; ++r) out_.emplace_back(3 * i + r, 3 * j + r, value);
  }

 private:
  Triplets& out_;
};

}  // namespace filum
