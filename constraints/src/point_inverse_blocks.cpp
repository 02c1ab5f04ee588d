#include "filum/constraints/point_inverse_blocks.hpp"

#include <algorithm>

namespace filum::constraints {

void PointInverseBlocks::keepIfUnchanged(const BlockInverse& inverse, const ConstraintProblem& problem) {
  const bool same = &inverse == inverse_ && inverse.revision() >= 0 && inverse.revision() == revision_ &&
                    problem.layout_revision == layout_ && problem.state_size == state_size_;
  inverse_ = &inverse;
  revision_ = inverse.revision();
  layout_ = problem.layout_revision;
  state_size_ = problem.state_size;
  if (slot_.size() < static_cast<std::size_t>(problem.dof_points)) slot_.resize(problem.dof_points, -1);
  if (same) return;
  for (int p : points_) slot_[p] = -1;
  points_.clear();
}

int PointInverseBlocks::listMissing(const ConstraintRows& rows) {
  missing_.clear();
  if (seen_.size() < slot_.size()) seen_.resize(slot_.size(), -1);
  ++calls_;
  touched_ = 0;
  for (int r = 0; r < rows.rows(); ++r)
    for (int t = rows.begin(r); t < rows.end(r); ++t) {
      const int p = rows.point(t);
      if (seen_[p] == calls_) continue;
      seen_[p] = calls_;
      ++touched_;
      if (slot_[p] == -1) missing_.push_back(p);
    }
  return static_cast<int>(missing_.size());
}

bool PointInverseBlocks::addMissing(const BlockInverse& inverse, const ConstraintProblem& problem,
                                    const std::vector<int>& point_body) {
  const int old = held(), total = old + static_cast<int>(missing_.size());
  if (total > maxPoints()) return false;
  if (h_.rows() < 3 * total) {  // grows only: doubled, the held blocks copied over
    MatX grown(std::min(6 * total, 3 * maxPoints()), std::min(6 * total, 3 * maxPoints()));
    grown.topLeftCorner(3 * old, 3 * old) = h_.topLeftCorner(3 * old, 3 * old);
    h_.swap(grown);
  }
  for (int p : missing_) {
    slot_[p] = held();
    points_.push_back(p);
  }
  // H's new columns: rows of A_b⁻¹ E_p at every held point of the same body, zero elsewhere
  // (block-diagonal operator). Eight right-hand sides per solve (solveBlockColumns).
  constexpr int kBatch = 8;
  const int added = total - old;
  h_.block(0, 3 * old, 3 * total, 3 * added).setZero();
  for (int first = 0; first < 3 * added;) {
    const int body = point_body[points_[old + first / 3]];
    const BodyBlock& block = problem.bodies[body];
    const int n = block.pointCount(), offset = block.offset();
    // Consecutive new points of this body, up to kBatch columns.
    int last = first;
    while (last < 3 * added && last - first < kBatch && point_body[points_[old + last / 3]] == body) ++last;
    if (batch_.rows() < 3 * n || batch_.cols() < kBatch)
      batch_.resize(std::max<Eigen::Index>(batch_.rows(), 2 * 3 * n), kBatch);  // grows only
    auto x = batch_.topLeftCorner(3 * n, last - first);
    x.setZero();
    int first_point = n;
    for (int k = first; k < last; ++k) {
      const int p = points_[old + k / 3] - offset;
      x(3 * p + k % 3, k - first) = 1.0;
      first_point = std::min(first_point, p);
    }
    inverse.solveBlockColumns(body, x, first_point);
    for (int k = first; k < last; ++k)
      for (int s = 0; s < total; ++s) {
        const int q = points_[s];
        if (point_body[q] == body) h_.block<3, 1>(3 * s, 3 * old + k) = x.col(k - first).segment<3>(3 * (q - offset));
      }
    first = last;
  }
  // The new rows: H is symmetric (A is).
  h_.block(3 * old, 0, 3 * added, 3 * old) = h_.block(0, 3 * old, 3 * old, 3 * added).transpose();
  return true;
}

}  // namespace filum::constraints
