// PointInverseBlocks: the 3 × 3 blocks (A⁻¹)_pq of a block-diagonal operator's inverse between
// the points constraint rows touch, kept while the operator does not change.
//
// A row is l_r = Σ_{t ∈ r} e_{p_t} ⊗ c_t (at most four points of a spline, two of a rod's
// segment), so
//   W_rk = l_rᵀ A⁻¹ l_k = Σ_{t ∈ r} Σ_{t' ∈ k} c_tᵀ (A⁻¹)_{p_t p_t'} c_t'
// needs A⁻¹ only between touched points: H = E_Pᵀ A⁻¹ E_P over the set P of those points, from
// the three columns A⁻¹ E_p of each (E_p: the unit vectors of point p's coordinates; H_qp is
// rows q of them, A being symmetric). That is 3 |P| band solves for the whole set, where W's
// columns A⁻¹ l_r cost one per row (c of them) — and H stays valid for as long as A does: an
// implicit step that reuses its matrix for many steps (BlockInverse::revision unchanged) solves
// only for the points its contacts move onto. Points of different bodies do not couple (the
// operator is block diagonal: not for coupled operators).
//
// History. H's block between two points is read from the columns of the one with the smaller
// point index, whichever arrived first (the columns are kept), so that the same A and points give
// the same bits whatever the cache held before: a run restored from a saved state repeats the
// original bit for bit.
//
// Storage: a slot per held point (slot order is arrival order), its three columns (9 n_b values),
// H as a dense 3P × 3P matrix; everything grows only, up to maxPoints() points and kMaxStored
// column values.
#pragma once

#include <cstddef>
#include <vector>

#include "filum/core/block_inverse.hpp"
#include "filum/core/constraint_problem.hpp"
#include "filum/core/constraint_rows.hpp"
#include "filum/core/types.hpp"

namespace filum::constraints {

class PointInverseBlocks {
 public:
  /// The most points held (H is then 3·512 square, 19 MB); beyond, rows go through W's columns.
  static constexpr int maxPoints() { return 512; }
  /// The most column values in use (64 MB; the buffer's capacity may reach twice that); beyond,
  /// the held points are forgotten, and if the rows' own points still exceed it (or
  /// maxPoints()) they go through W's columns.
  static constexpr std::size_t kMaxStored = std::size_t{1} << 23;

  /// Forgets every block unless `inverse` is the operator, at the revision and on the layout
  /// of the last call (revision −1: it may change at any call, nothing is kept).
  void keepIfUnchanged(const BlockInverse& inverse, const ConstraintProblem& problem);
  /// The points of `rows` not held yet, listed for addMissing(); their count. Also counts the
  /// distinct points of `rows` (touched()).
  int listMissing(const ConstraintRows& rows);
  /// The distinct points of the rows of the last listMissing.
  int touched() const { return touched_; }
  /// Solves the listed points' columns (3 each, batched per body) and extends H. `point_body`:
  /// the body of each scene point. Over maxPoints() or kMaxStored, forgets the held points and
  /// takes all the rows' points; false if those alone exceed a limit (nothing added).
  bool addMissing(const BlockInverse& inverse, const ConstraintProblem& problem, const std::vector<int>& point_body);

  /// The slot of a held point (−1: not held).
  int slot(int point) const { return point < static_cast<int>(slot_.size()) ? slot_[point] : -1; }
  /// H's 3 × 3 block between held slots i and j.
  auto block(int i, int j) const { return h_.block<3, 3>(3 * i, 3 * j); }
  /// H's three columns of slot j over every held slot (3 held() rows).
  auto columns(int j) const { return h_.block(0, 3 * j, 3 * held(), 3); }
  int held() const { return static_cast<int>(points_.size()); }

 private:
  /// Drops every held point (their columns and blocks).
  void forget();
  /// (A⁻¹)_{p_i p_j} for held slots i, j on one body, from the kept columns (see History).
  Eigen::Matrix3d blockFromColumns(int i, int j, const ConstraintProblem& problem,
                                   const std::vector<int>& point_body) const;

  const BlockInverse* inverse_ = nullptr;
  long revision_ = -1;
  long layout_ = -1;
  Eigen::Index state_size_ = -1;
  std::vector<int> slot_;     // per scene point: its slot or −1
  std::vector<int> points_;   // per slot: the point
  std::vector<int> missing_;  // listMissing's points, in order of first appearance
  std::vector<int> touched_points_;  // listMissing's rows' distinct points, in that order
  std::vector<long> seen_;    // per scene point: the listMissing call that last saw it
  long calls_ = 0;
  int touched_ = 0;
  MatX h_;                    // H (3 held() leading rows and columns used)
  MatX batch_;                // the columns A_b⁻¹ E_p being solved (3 n_b × 8)
  std::vector<double> pool_;        // the held points' columns, slot by slot (grows only)
  std::vector<std::size_t> offset_;  // per slot: where its columns start in pool_
  std::size_t pool_size_ = 0;        // pool_'s values in use
};

}  // namespace filum::constraints
