// SupportJacobian: accumulates the 3 × 3 blocks ∂²e/∂q_i∂q_j of an energy density e evaluated at
// quadrature nodes, where e depends on the control points only through P'(s) = Σ b'_i q_i and
// P''(s) = Σ b''_i q_i. By the chain rule
//   ∂²e/∂q_i∂q_j = Σ_{u,w ∈ {P', P''}} c^u_i c^w_j ∂²e/∂u∂w   (c^{P'} = b', c^{P''} = b''),
// a sum of outer products over the d + 1 control points of the node's support. Nodes of one
// polynomial piece share that support, so their blocks are summed locally and emitted once per
// piece into the step matrix: (d+1)(d+2)/2 symmetric block pairs per piece instead of per node.
#pragma once

#include <array>

#include "filum/core/jacobian_accumulator.hpp"
#include "filum/core/types.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::mechanics {

class SupportJacobian {
 public:
  static constexpr int kMax = 3 * geometry::BasisRow::kMaxSupport;

  /// Starts accumulating; blocks go to `out` at global point base + local, scaled by `factor`
  /// (e.g. −k_factor to turn a Hessian into k_factor·K).
  SupportJacobian(JacobianAccumulator& out, int base_point, double factor)
      : out_(out), base_(base_point), factor_(factor) {}
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
    full_ = true;
  }
  /// block(i, j) += c[i] c[j] H for a symmetric H: only the blocks i >= j are accumulated (the
  /// others are their transposes), half the work of add(c, c, H).
  void addSymmetric(const std::array<double, geometry::BasisRow::kMaxSupport>& c, const Eigen::Matrix3d& H) {
    for (int i = 0; i < count_; ++i)
      for (int j = 0; j <= i; ++j) local_.block<3, 3>(3 * i, 3 * j) += (c[i] * c[j]) * H;
    dirty_ = true;
  }
  /// Emits the current piece's blocks: the diagonal ones, and each off-diagonal pair once —
  /// symmetrised when add() was used (the sum of Hessian terms is symmetric; its parts need not
  /// be), as accumulated when only addSymmetric() was.
  void flush() {
    if (!dirty_) return;
    const int origin = base_ + first_;
    for (int i = 0; i < count_; ++i) {
      out_.addBlock(origin + i, origin + i, factor_ * local_.block<3, 3>(3 * i, 3 * i));
      for (int j = 0; j < i; ++j) {
        const Eigen::Matrix3d lower = local_.block<3, 3>(3 * i, 3 * j);
        if (full_)
          out_.addBlockPair(origin + i, origin + j, (0.5 * factor_) * (lower + local_.block<3, 3>(3 * j, 3 * i).transpose()));
        else
          out_.addBlockPair(origin + i, origin + j, factor_ * lower);
      }
    }
    local_.topLeftCorner(3 * count_, 3 * count_).setZero();
    dirty_ = false;
    full_ = false;
  }

 private:
  JacobianAccumulator& out_;
  int base_;
  double factor_;
  int first_ = -1, count_ = 0;
  bool dirty_ = false;
  bool full_ = false;  // add() was used: the local matrix holds every block
  Eigen::Matrix<double, kMax, kMax> local_ = Eigen::Matrix<double, kMax, kMax>::Zero();
};

}  // namespace filum::mechanics
