#include "filum/constraints/lagrange_multiplier_solver.hpp"

#include <algorithm>

#include "filum/core/scene.hpp"

namespace filum::constraints {

void LagrangeMultiplierSolver::solve(const Scene& scene, const ConstraintRows& rows, const BlockInverse& inverse,
                                     VecX& a) {
  const int c = rows.rows();
  const auto& bodies = scene.bodies();
  y_.resize(a.size(), c);
  w_.resize(c, c);
  rhs_.resize(c);

  // Columns of M⁻¹ Lᵀ: scatter row r, then solve only the bodies it touches.
  for (int r = 0; r < c; ++r) {
    auto column = y_.col(r);
    column.setZero();
    touched_.clear();
    for (int t = rows.begin(r); t < rows.end(r); ++t) {
      column.segment<3>(3 * rows.point(t)) += rows.coeff(t);
      touched_.push_back(scene.bodyOfPoint(rows.point(t)));
    }
    std::sort(touched_.begin(), touched_.end());
    touched_.erase(std::unique(touched_.begin(), touched_.end()), touched_.end());
    for (int b : touched_) {
      const MechanicalState& body = *bodies[b];
      inverse.solveBlock(b, column.segment(3 * body.offset(), 3 * body.pointCount()));
    }
  }

  // W = L M⁻¹ Lᵀ (sparse rows of L: O(c² d)) and E − L A_t.
  for (int r = 0; r < c; ++r) {
    rhs_[r] = rows.rhs(r);
    for (int t = rows.begin(r); t < rows.end(r); ++t) {
      const int p = rows.point(t);
      rhs_[r] -= rows.coeff(t).dot(a.segment<3>(3 * p));
    }
  }
  for (int r = 0; r < c; ++r)
    for (int k = 0; k < c; ++k) {
      double sum = 0.0;
      for (int t = rows.begin(r); t < rows.end(r); ++t) sum += rows.coeff(t).dot(y_.col(k).segment<3>(3 * rows.point(t)));
      w_(r, k) = sum;
    }

  // λ = W⁻¹ (E − L A_t), A = A_t + M⁻¹ Lᵀ λ.
  ldlt_.compute(w_);
  lambda_ = ldlt_.solve(rhs_);
  a.noalias() += y_ * lambda_;
}

}  // namespace filum::constraints
