// BlockInverse: applies the inverse of a block-diagonal system matrix, one block per body —
// the mass matrix M for explicit steps (A = M⁻¹B, paper eq. 3), or the matrix of an implicit
// step (M − h D − h² K). Constraint solvers work through it, so the acceleration decomposition
// of paper §4 serves explicit and implicit integrators alike.
#pragma once

#include "filum/core/types.hpp"

namespace filum {

class BlockInverse {
 public:
  virtual ~BlockInverse() = default;
  /// In place x := A_b⁻¹ x for body b's block x (3 n_b values, x0 y0 z0 x1 ...).
  virtual void solveBlock(int body, Eigen::Ref<VecX> x) const = 0;
};

}  // namespace filum
