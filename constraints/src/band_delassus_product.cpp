#include "filum/constraints/band_delassus_product.hpp"

#include <algorithm>

#include "filum/constraints/band_solve_cost.hpp"
#include "filum/core/growing_vector.hpp"

namespace filum::constraints {

bool BandDelassusProduct::prepare(const ConstraintRows& rows, const BlockInverse& inverse, const ConstraintProblem& problem,
                                  const std::vector<int>& point_body) {
  ready_ = false;
  c_ = rows.rows();
  if (inverse.coupled() || c_ == 0) return false;
  resizeGrowing(body_seen_, problem.bodies.size());
  std::fill(body_seen_.begin(), body_seen_.end(), 0);
  bodies_.clear();
  const int terms = rows.end(c_ - 1);
  for (int t = 0; t < terms; ++t) {
    const int b = point_body[rows.point(t)];
    if (!body_seen_[b]) {
      body_seen_[b] = 1;
      bodies_.push_back(b);
    }
  }
  // Scatter and gather, 3 multiply-adds a term each, and a band solve per body.
  double cost = 6.0 * terms;
  for (int b : bodies_) {
    BandBlocks band;
    if (!inverse.bandBlocks(b, band)) return false;
    cost += bandSolveMultiplyAdds(band);
  }
  cost_ = cost;
  inverse_ = &inverse;
  problem_ = &problem;
  if (point_vector_.size() < 3 * problem.dof_points) point_vector_.resize(3 * problem.dof_points);  // grows only
  ready_ = true;
  return true;
}

void BandDelassusProduct::multiply(const ConstraintRows& rows, const Eigen::Ref<const VecX>& x, Eigen::Ref<VecX> out) {
  // W x = L A⁻¹ (Lᵀ x), A⁻¹ body by body.
  const int c = c_;
  for (int b : bodies_) {
    const BodyBlock& body = problem_->bodies[b];
    point_vector_.segment(3 * body.offset(), 3 * body.pointCount()).setZero();
  }
  for (int r = 0; r < c; ++r)
    if (x[r] != 0.0) rows.addTransposed(r, x[r], point_vector_);
  for (int b : bodies_) {
    const BodyBlock& body = problem_->bodies[b];
    inverse_->solveBlock(b, point_vector_.segment(3 * body.offset(), 3 * body.pointCount()));
  }
  for (int r = 0; r < c; ++r) out[r] = rows.dot(r, point_vector_);
}

}  // namespace filum::constraints
