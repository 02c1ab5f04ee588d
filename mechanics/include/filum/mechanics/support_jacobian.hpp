// SupportJacobian: accumulates the 3 × 3 blocks ∂²e/∂q_i∂q_j of an energy density e evaluated at
// quadrature nodes, where e depends on the control points only through P'(s) = Σ b'_i q_i and
// P''(s) = Σ b''_i q_i. By the chain rule
//   ∂²e/∂q_i∂q_j = Σ_{u,w ∈ {P', P''}} c^u_i c^w_j ∂²e/∂u∂w   (c^{P'} = b', c^{P''} = b''),
// a sum of outer products over the d + 1 control points of the node's support. Nodes of one
// polynomial piece share that support, so their blocks are summed locally and emitted once per
// piece as triplets: (3(d+1))² entries per piece instead of per node.
#pragma once

#include <array>

#include "filum/core/types.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::mechanics {

class SupportJacobian {
 public:
  static constexpr int kMax = 3 * geometry::BasisRow::kMaxSupport;

  /// Starts accumulating; entries go to `out` at global row/column 3·base + local, scaled by
  /// `factor` (e.g. −k_factor to turn a Hessian into k_factor·K).
  SupportJacobian(Triplets& out, int base_point, double factor) : out_(out), base_(base_point), factor_(factor) {}
  ~SupportJacobian() { flush(); }
  SupportJacobian(const SupportJacobian&) = delete;
  SupportJacobian& operator=(const SupportJacobian&) = delete;

  /// Moves to the support of `row` (emits the previous piece if the support changes).
  void begin(const geometry::BasisRow& row) {
    if (row.first != first_ || row.count != count_) {
      flush();
      first_ = row.first;
      count_ = row.count;
    }
  }
  /// block(i, j) += ci[i] cj[j] H for the current support (ci, cj: b, b' or b'' values).
  void add(const std::array<double, geometry::BasisRow::kMaxSupport>& ci,
           const std::array<double, geometry::BasisRow::kMaxSupport>& cj, const Eigen::Matrix3d& H) {
    for (int i = 0; i < count_; ++i)
      for (int j = 0; j < count_; ++j) local_.block<3, 3>(3 * i, 3 * j) += (ci[i] * cj[j]) * H;
    dirty_ = true;
  }
  /// Emits the current piece's blocks.
  void flush() {
    if (!dirty_) return;
    const int m = 3 * count_, origin = 3 * (base_ + first_);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) out_.emplace_back(origin + i, origin + j, factor_ * local_(i, j));
    local_.topLeftCorner(m, m).setZero();
    dirty_ = false;
  }

 private:
  Triplets& out_;
  int base_;
  double factor_;
  int first_ = -1, count_ = 0;
  bool dirty_ = false;
  Eigen::Matrix<double, kMax, kMax> local_ = Eigen::Matrix<double, kMax, kMax>::Zero();
};

}  // namespace filum::mechanics
