// BandMatrix: a random symmetric positive definite block band matrix A per body (a thread's or a
// rod's step matrix: 3 × 3 blocks, neighbours within `range` groups, a rod's frame triples
// interleaved with its points), as a BlockInverse that exposes its band and solves by its dense
// inverse; and W = L A⁻¹ Lᵀ of rows on its bodies, formed densely — for the contact solvers' tests.
#pragma once

#include <random>
#include <vector>

#include <Eigen/LU>

#include "filum/core/block_inverse.hpp"
#include "filum/core/constraint_problem.hpp"
#include "filum/core/constraint_rows.hpp"
#include "filum/core/types.hpp"

namespace filum::test {

/// Block band matrices A_b, one per body, exposed as BandBlocks, with solves by their dense
/// inverses. A body with internal groups interleaves them with its points (point k at
/// group 2k, an internal triple at 2k + 1), as a rod's step matrix does.
class BandMatrix final : public BlockInverse {
 public:
  struct Body {
    int points = 0, range = 0;
    bool internal = false;
    bool indefinite = false;  // the first group's diagonal made negative (an indefinite A)
  };
  BandMatrix(const std::vector<Body>& bodies, std::mt19937& rng) {
    std::normal_distribution<double> normal(0.0, 1.0);
    for (const Body& spec : bodies) {
      Band band;
      band.groups = spec.internal ? 2 * spec.points : spec.points;
      band.range = spec.range;
      const int n = band.groups;
      MatX& dense = band.dense;
      dense = MatX::Zero(3 * n, 3 * n);
      for (int i = 0; i < n; ++i)
        for (int j = std::max(0, i - spec.range); j < i; ++j) {
          Eigen::Matrix3d b;
          for (int a = 0; a < 3; ++a)
            for (int c = 0; c < 3; ++c) b(a, c) = 0.3 * normal(rng);
          dense.block<3, 3>(3 * i, 3 * j) = b;
          dense.block<3, 3>(3 * j, 3 * i) = b.transpose();
        }
      // Diagonally dominant: symmetric positive definite.
      for (int i = 0; i < 3 * n; ++i) dense(i, i) = dense.row(i).cwiseAbs().sum() + 1.0;
      if (spec.indefinite)
        for (int i = 0; i < 3; ++i) dense(i, i) = -dense(i, i);  // still invertible (dominant), not definite
      band.blocks.assign(static_cast<std::size_t>(n) * (spec.range + 1), Eigen::Matrix3d::Zero());
      for (int i = 0; i < n; ++i)
        for (int j = std::max(0, i - spec.range); j <= i; ++j)
          band.blocks[i * (spec.range + 1) + (j - i + spec.range)] = dense.block<3, 3>(3 * i, 3 * j);
      for (int k = 0; k < spec.points; ++k) band.point_group.push_back(spec.internal ? 2 * k : k);
      bands_.push_back(std::move(band));
    }
  }
  /// The operator's revision (BlockInverse::revision): −1, none, unless set — a solver keeps
  /// what it computed for the next call on the same operator only when it is >= 0.
  long revision() const override { return revision_; }
  void setRevision(long revision) { revision_ = revision; }
  /// x := (A_b⁻¹)_pp x, by the dense inverse (the products with W through the band take it).
  void solveBlock(int body, Eigen::Ref<VecX> x) const override {
    const Band& band = bands_[body];
    if (band.point_inverse.size() == 0) band.point_inverse = pointInverse(body);
    x = band.point_inverse * x;
  }
  bool bandBlocks(int body, BandBlocks& out) const override {
    if (body < 0 || body >= static_cast<int>(bands_.size())) return false;
    const Band& band = bands_[body];
    out.groups = band.groups;
    out.range = band.range;
    out.lower = band.blocks.data();
    out.point_group = band.point_group.data();
    return true;
  }
  /// A_b⁻¹'s blocks within max(range, the band's range) block diagonals, from the dense inverse.
  bool inverseBandBlocks(int body, int range, std::vector<Eigen::Matrix3d>& out) const override {
    if (body < 0 || body >= static_cast<int>(bands_.size())) return false;
    const Band& band = bands_[body];
    const int wide = std::max(range, band.range);
    const MatX inverse = band.dense.inverse();
    out.assign(static_cast<std::size_t>(band.groups) * (wide + 1), Eigen::Matrix3d::Zero());
    for (int i = 0; i < band.groups; ++i)
      for (int j = std::max(0, i - wide); j <= i; ++j)
        out[i * (wide + 1) + (j - i + wide)] = inverse.block<3, 3>(3 * i, 3 * j);
    return true;
  }
  /// (A_b⁻¹)_pp: the points' block of the inverse (internal DOFs carry no force).
  MatX pointInverse(int body) const {
    const Band& band = bands_[body];
    const MatX inverse = band.dense.inverse();
    const int points = static_cast<int>(band.point_group.size());
    MatX out(3 * points, 3 * points);
    for (int i = 0; i < points; ++i)
      for (int j = 0; j < points; ++j)
        out.block<3, 3>(3 * i, 3 * j) = inverse.block<3, 3>(3 * band.point_group[i], 3 * band.point_group[j]);
    return out;
  }

 private:
  struct Band {
    int groups = 0, range = 0;
    std::vector<Eigen::Matrix3d> blocks;
    std::vector<int> point_group;
    MatX dense;
    mutable MatX point_inverse;  // (A⁻¹)_pp, formed on the first solve
  };
  std::vector<Band> bands_;
  long revision_ = -1;
};

/// W = L A⁻¹ Lᵀ of rows on the bodies (block diagonal A⁻¹ over the bodies' points).
inline MatX delassus(const ConstraintRows& rows, const BandMatrix& a, const ConstraintProblem& problem) {
  const int c = rows.rows();
  MatX l = MatX::Zero(c, 3 * problem.dof_points);
  for (int r = 0; r < c; ++r)
    for (int t = rows.begin(r); t < rows.end(r); ++t) l.block<1, 3>(r, 3 * rows.point(t)) += rows.coeff(t).transpose();
  MatX inverse = MatX::Zero(3 * problem.dof_points, 3 * problem.dof_points);
  for (std::size_t b = 0; b < problem.bodies.size(); ++b) {
    const BodyBlock& body = problem.bodies[b];
    inverse.block(3 * body.offset(), 3 * body.offset(), 3 * body.pointCount(), 3 * body.pointCount()) =
        a.pointInverse(static_cast<int>(b));
  }
  return l * inverse * l.transpose();
}

}  // namespace filum::test
