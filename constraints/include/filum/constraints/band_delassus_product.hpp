// BandDelassusProduct: products with the Delassus matrix W = L A⁻¹ Lᵀ without W, through the band
// factors of A body by body: W x = L (A⁻¹ (Lᵀ x)) — the rows' forces on their points (Lᵀ x), one
// band solve per body the rows touch (A is block diagonal over the bodies: !coupled()), and each
// row's reading of the response (L ·). O(terms + Σ_b groups_b · range_b) multiply-adds against
// c² for W dense: cheaper with many rows on few points (a rod on a table, a wire lying along a
// catheter), where it also spares forming W at all (O(c² terms)).
//
// prepare() is taken once per solve, before W would be formed: it lists the rows' bodies and
// prices the product; multiply() is then valid while the rows, A and the problem are unchanged.
// The workspace only grows: a steady step allocates nothing.
#pragma once

#include <vector>

#include "filum/core/block_inverse.hpp"
#include "filum/core/constraint_problem.hpp"
#include "filum/core/constraint_rows.hpp"
#include "filum/core/types.hpp"

namespace filum::constraints {

class BandDelassusProduct {
 public:
  /// The rows' bodies and the product's cost; false (nothing to offer) when A couples bodies, a
  /// body has no band factor, or there are no rows. `point_body`: the body of each point.
  bool prepare(const ConstraintRows& rows, const BlockInverse& inverse, const ConstraintProblem& problem,
               const std::vector<int>& point_body);
  /// Prepared, and cheaper than the dense product c² (c: the rows of the prepare() call).
  bool cheaperThanDense() const { return ready_ && kDenseProductRateRatio * cost_ < static_cast<double>(c_) * c_; }
  /// Multiply-adds of one product (0 when not prepared).
  double cost() const { return ready_ ? cost_ : 0.0; }
  /// out := W x (c values), x and out of the prepared rows' size. Only after a successful prepare().
  void multiply(const ConstraintRows& rows, const Eigen::Ref<const VecX>& x, Eigen::Ref<VecX> out);

  /// The dense product's c² multiply-adds run as long vectorized dot products, about twice the
  /// band sweeps' rate (the same ratio as the contact Newton's between the dense and the envelope LU).
  static constexpr double kDenseProductRateRatio = 2.0;

 private:
  bool ready_ = false;
  int c_ = 0;
  double cost_ = 0.0;
  const BlockInverse* inverse_ = nullptr;
  const ConstraintProblem* problem_ = nullptr;
  std::vector<int> bodies_;      // the bodies the rows act on
  std::vector<char> body_seen_;  // per problem body
  VecX point_vector_;            // Lᵀ x, then A⁻¹ Lᵀ x (3 per point)
};

}  // namespace filum::constraints
