// SupportHessianCache: the Hessian ∇²E of a continuous energy, kept as the 3 × 3 blocks of each
// support (quadrature piece) for the positions it was computed at, so that a second request at
// the same positions replays the blocks instead of evaluating second derivatives again.
//
// Why: in an implicit step with lagged stiffness-proportional damping (RayleighDamping
// "per_step") the elastic Jacobian K is asked for twice at the step's first state — by the
// damper, for its β K, and by the step matrix, for −κh² K. For a real suture the second
// derivatives of the curvature density were over half of the step (apps/bench/bench_realtime,
// suture_implicit: 0.065 -> 0.048 ms per simulated ms with the cache and the closed-form Hessian).
//
// The key is the body's 3n coordinates, compared exactly: any change of the positions recomputes.
// Storage is sized by reset() (the field's init, which a layout change re-runs) and reused.
#pragma once

#include <array>
#include <vector>

#include "filum/core/jacobian_accumulator.hpp"
#include "filum/core/types.hpp"
#include "filum/geometry/spline_basis.hpp"
#include "filum/mechanics/curve_quadrature.hpp"

namespace filum::mechanics {

class SupportHessianCache {
 public:
  static constexpr int kStride = geometry::BasisRow::kMaxSupport * (geometry::BasisRow::kMaxSupport + 1) / 2;

  /// Sizes the storage for `pieces` supports and a body of `points` points; forgets the blocks.
  void reset(std::size_t pieces, int points) {
    blocks_.assign(pieces * kStride, Eigen::Matrix3d::Zero());
    key_.resize(3 * Eigen::Index(points));
    valid_ = false;
  }

  /// out += −k_factor ∇²E(q) at global point `base`: q is the body's 3n coordinates; when they
  /// differ from the kept ones, compute(piece index, q, blocks) fills each support's blocks
  /// (pair (a, b <= a) at k = a (a + 1) / 2 + b, as JacobianAccumulator::addSupportBlocks) first.
  template <class Compute>
  void add(const std::vector<QuadraturePiece>& pieces, const Eigen::Ref<const VecX>& q, double k_factor, int base,
           JacobianAccumulator& out, Compute&& compute) {
    if (!valid_ || key_ != q) {
      for (std::size_t p = 0; p < pieces.size(); ++p) compute(p, q.data(), &blocks_[p * kStride]);
      key_ = q;
      valid_ = true;
    }
    std::array<Eigen::Matrix3d, kStride> scaled;
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      const int count = pieces[p].count, pairs = count * (count + 1) / 2;
      for (int k = 0; k < pairs; ++k) scaled[k] = -k_factor * blocks_[p * kStride + k];
      out.addSupportBlocks(base + pieces[p].first, count, scaled.data());
    }
  }

 private:
  std::vector<Eigen::Matrix3d> blocks_;  // ∇²E per support, kStride slots each
  VecX key_;                             // the positions they are for
  bool valid_ = false;
};

}  // namespace filum::mechanics
