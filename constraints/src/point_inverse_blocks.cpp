#include "filum/constraints/point_inverse_blocks.hpp"

#include <algorithm>

#include "filum/core/growing_vector.hpp"

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
  forget();
}

void PointInverseBlocks::forget() {
  for (int p : points_) slot_[p] = -1;
  points_.clear();
  offset_.clear();
  pool_size_ = 0;
}

int PointInverseBlocks::listMissing(const ConstraintRows& rows) {
  missing_.clear();
  touched_points_.clear();
  if (seen_.size() < slot_.size()) seen_.resize(slot_.size(), -1);
  ++calls_;
  touched_ = 0;
  for (int r = 0; r < rows.rows(); ++r)
    for (int t = rows.begin(r); t < rows.end(r); ++t) {
      const int p = rows.point(t);
      if (seen_[p] == calls_) continue;
      seen_[p] = calls_;
      ++touched_;
      touched_points_.push_back(p);
      if (slot_[p] == -1) missing_.push_back(p);
    }
  return static_cast<int>(missing_.size());
}

Eigen::Matrix3d PointInverseBlocks::blockFromColumns(int i, int j, const ConstraintProblem& problem,
                                                     const std::vector<int>& point_body) const {
  // (A⁻¹)_{p_i p_j} from the columns of the point with the smaller index, whatever order the two
  // arrived in: the same bits for the same A and points, so W does not depend on the cache's
  // history (a run restored from a saved state repeats the original bit for bit).
  const int pi = points_[i], pj = points_[j];
  if (pi < pj) return blockFromColumns(j, i, problem, point_body).transpose();
  const BodyBlock& body = problem.bodies[point_body[pj]];
  const int n3 = 3 * body.pointCount();
  const double* g = pool_.data() + offset_[j];  // column b of p_j: g[b * n3 + row]
  Eigen::Matrix3d block;
  for (int b = 0; b < 3; ++b)
    for (int a = 0; a < 3; ++a) block(a, b) = g[b * n3 + 3 * (pi - body.offset()) + a];
  return block;
}

bool PointInverseBlocks::addMissing(const BlockInverse& inverse, const ConstraintProblem& problem,
                                    const std::vector<int>& point_body) {
  // The new points' columns A_b⁻¹ E_p (3 × 3 n_b values each) are kept: H's blocks are read from
  // the column of the smaller point index of each pair (blockFromColumns). Over the limits, the
  // held points are forgotten and the rows' points taken afresh, so that whether the limits
  // refuse depends on the rows only, not on what was held (a restored run takes the same path).
  auto storedWith = [&](std::size_t base) {
    for (int p : missing_) base += 9 * static_cast<std::size_t>(problem.bodies[point_body[p]].pointCount());
    return base;
  };
  std::size_t stored = storedWith(pool_size_);
  if (held() + static_cast<int>(missing_.size()) > maxPoints() || stored > kMaxStored) {
    forget();
    assignGrowing(missing_, touched_points_);
    stored = storedWith(0);
    if (static_cast<int>(missing_.size()) > maxPoints() || stored > kMaxStored) return false;
  }
  const int old = held(), total = old + static_cast<int>(missing_.size());
  if (h_.rows() < 3 * total) {  // grows only: doubled, the held blocks copied over
    MatX grown(std::min(6 * total, 3 * maxPoints()), std::min(6 * total, 3 * maxPoints()));
    grown.topLeftCorner(3 * old, 3 * old) = h_.topLeftCorner(3 * old, 3 * old);
    h_.swap(grown);
  }
  resizeGrowing(pool_, stored);
  for (int p : missing_) {
    slot_[p] = held();
    points_.push_back(p);
    offset_.push_back(pool_size_);
    pool_size_ += 9 * static_cast<std::size_t>(problem.bodies[point_body[p]].pointCount());
  }
  // The columns, eight right-hand sides per solve (solveBlockColumns), consecutive new points of
  // one body in a batch.
  constexpr int kBatch = 8;
  const int added = total - old;
  for (int first = 0; first < 3 * added;) {
    const int body = point_body[points_[old + first / 3]];
    const BodyBlock& block = problem.bodies[body];
    const int n = block.pointCount(), offset = block.offset();
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
      std::copy(x.col(k - first).data(), x.col(k - first).data() + 3 * n,
                pool_.data() + offset_[old + k / 3] + static_cast<std::size_t>(k % 3) * 3 * n);
    first = last;
  }
  // H's new rows and columns: zero between bodies (a block-diagonal operator), else the block.
  for (int j = old; j < total; ++j)
    for (int i = 0; i < total; ++i) {
      const bool same_body = point_body[points_[i]] == point_body[points_[j]];
      const Eigen::Matrix3d block = same_body ? blockFromColumns(i, j, problem, point_body) : Eigen::Matrix3d::Zero();
      h_.block<3, 3>(3 * i, 3 * j) = block;
      if (i != j) h_.block<3, 3>(3 * j, 3 * i) = block.transpose();
    }
  return true;
}

}  // namespace filum::constraints
