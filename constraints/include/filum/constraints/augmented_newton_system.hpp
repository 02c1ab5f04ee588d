// AugmentedNewtonSystem: the linear system of one contact Newton step, J_SS Δ_S = r, solved
// without the dense Delassus matrix — through A's band and the rows' sparsity.
//
// Each Newton row r of the solved set S has the form (contact_newton.hpp)
//   J_r = Σ_k b_rk W_k + Σ_m c_rm e_mᵀ,      W = L A⁻¹ Lᵀ,
// with k and m rows of r's own contact (b = ρ_r, c = ρ_r R_r on a tied row; the three rows n, t1,
// t2 on a sliding pair). With u = A⁻¹ L_Sᵀ Δ_S the system is the augmented one
//   [ A        −L_Sᵀ ] [ u   ]   [ 0 ]
//   [ B L_S     C    ] [ Δ_S ] = [ r ],
// whose Schur complement on Δ_S is J_SS (eliminating u gives B L_S A⁻¹ L_Sᵀ + C). It is as sparse
// as A and L: A is a band of 3 × 3 blocks per body (a thread's points couple only to their
// neighbours), a row acts on a few points. Its unknowns are ordered along each body — every
// point's three coordinates, then the rows whose last point it is — so that each row follows the
// points it acts on: a row against an obstacle adds a few entries to the band; a contact between
// far parts of one thread (a knot's self-contacts) widens the envelope from its first point to
// itself. The envelope LU (ProfileLu) then costs Σ_i (envelope width)² instead of |S|³/3, and the
// caller takes the dense LU when that is cheaper.
//
// Bodies that touch each other are merged along each other (orderGroups): a wire inside a
// catheter, or a thread lying along another, touches it all along, and with the bodies one after
// the other every row between them would reach back across the whole first body. Each group of
// a later body takes the key of the earliest group of the bodies before it that a row joins it to
// (groups no row joins take the key of the group before them along the body, or of its first
// joined group for those before that), and the groups are sorted by key, ties in the bodies'
// order: the wire's point lands beside the catheter's point it lies on, and the envelope stays a
// few groups wide. A body that touches no earlier one keeps its place after them, so one body, or
// bodies that only meet obstacles, keep the order along each body. The order is a permutation of
// whole groups: A's band stays symmetric in it (both triangles are widened), and a row still
// follows every point it acts on. Where bodies merge, both orders are laid out and the cheaper
// envelope kept: two threads that cross once would otherwise have the whole second one placed
// between two groups of the first, whose band would then reach across it. A body that touches two
// earlier ones is merged along the one its lowest key comes from; its rows to the other reach as
// far as they did with the bodies in sequence.
//
// Pivots. Eliminated in this order, a row's pivot is c_rr + δ + (the row's own J_rr given the
// points before it): the size of J's diagonal (unit, by ρ), not the small compliance alone; a
// row redundant with earlier ones (spheres every 0.3 mm on a thread of 1 mm spans) has a pivot
// of the size of the Levenberg shift δ — as it has in J_SS itself. A's pivots are its own (M
// dominates an implicit step's matrix). Tied rows scaled by 1/ρ make the system quasi-definite
// (Vanderbei 1995: a factorization exists in any order); sliding pairs (non-symmetric rows) and an indefinite A (a
// compressed thread) are not covered by that argument: a zero or non-finite pivot is refused,
// and ContactNewton takes the dense LU when the solution is not finite.
//
// build() lays out the order and the envelope (enough for cost()); factor() allocates the
// envelope's storage and fills it, so a system the caller does not take costs no memory.
#pragma once

#include <utility>
#include <vector>

#include "filum/constraints/profile_lu.hpp"
#include "filum/core/block_inverse.hpp"
#include "filum/core/constraint_problem.hpp"
#include "filum/core/constraint_rows.hpp"

namespace filum::constraints {

/// A Newton row's Jacobian in terms of W's rows: J_r = Σ b[i] W_{bk[i]} + Σ c[j] e_{ck[j]}.
struct NewtonRowForm {
  int nb = 0, nc = 0;
  int bk[3] = {0, 0, 0};
  double b[3] = {0.0, 0.0, 0.0};
  int ck[4] = {0, 0, 0, 0};
  double c[4] = {0.0, 0.0, 0.0, 0.0};
  void addW(int k, double value) {
    bk[nb] = k;
    b[nb++] = value;
  }
  void addUnit(int k, double value) {
    for (int j = 0; j < nc; ++j)
      if (ck[j] == k) {
        c[j] += value;
        return;
      }
    ck[nc] = k;
    c[nc++] = value;
  }
};

class AugmentedNewtonSystem {
 public:
  /// Orders and lays out the augmented matrix for the solved rows `solved` (their forms in
  /// `forms`, indexed by row; `row_position` maps a row to its index in `solved`, −1 if not
  /// solved), with δ added to the rows' diagonal. False when a body the rows act on has no band
  /// (BlockInverse::bandBlocks), or a form names a row that is not solved: the dense step then.
  bool build(const ConstraintRows& rows, const std::vector<int>& solved, const std::vector<int>& row_position,
             const std::vector<NewtonRowForm>& forms, double damping, const BlockInverse& inverse,
             const ConstraintProblem& problem, const std::vector<int>& point_body);
  /// The envelope LU's multiply-adds (after build).
  double cost() const { return lu_.cost(); }
  /// Lays the envelope's storage out, fills the values and factors; false on a zero or non-finite
  /// pivot, and with positive_pivots on a pivot <= 0 (ProfileLu::factor).
  bool factor(bool positive_pivots = false);
  /// rhs (in solved order) := Δ_S.
  void solve(Eigen::Ref<VecX> rhs);

 private:
  /// Sets rank_ (group → place in the order): with `merge`, bodies merged along the rows between
  /// them (header), else the bodies one after the other. True when that is not the identity.
  bool orderGroups(bool merge);
  /// Places the rows after their points in rank_'s order and lays the envelope out; false as build.
  bool layOut();
  /// The first unknown of the group at place `rank`.
  int groupPosition(int rank) const;
  /// The global group (over the touched bodies' bands, bodies one after the other) of point p,
  /// −1 if its body is not touched.
  int groupOfPoint(int p) const;
  /// The place in the order of point p's group.
  int rankOfPoint(int p) const { return rank_[groupOfPoint(p)]; }

  const ConstraintRows* rows_ = nullptr;
  const std::vector<int>* solved_ = nullptr;
  const std::vector<int>* row_position_ = nullptr;
  const std::vector<NewtonRowForm>* forms_ = nullptr;
  const ConstraintProblem* problem_ = nullptr;
  const std::vector<int>* point_body_ = nullptr;
  double damping_ = 0.0;

  std::vector<int> body_base_;          // per problem body: its first global group, −1 if untouched
  std::vector<BandBlocks> bands_;       // per problem body (valid where body_base_ >= 0)
  std::vector<int> touched_;            // touched bodies in order
  int groups_ = 0;                      // global groups
  std::vector<double> key_;             // per global group: its sort key (orderGroups)
  std::vector<std::pair<double, int>> by_key_;  // (key, global group), sorted
  std::vector<int> rank_;               // per global group: its place in the order
  std::vector<int> merged_rank_;        // the merged order's rank_, while the other is laid out
  std::vector<std::pair<int, int>> by_anchor_;  // (anchor group, solved index), sorted
  std::vector<int> rows_before_;        // per place in the order: solved rows placed before its coordinates
  std::vector<int> row_unknown_;        // per solved index: its unknown's position
  ProfileLu lu_;
  VecX x_;
};

}  // namespace filum::constraints
