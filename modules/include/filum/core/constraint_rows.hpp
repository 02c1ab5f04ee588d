// ConstraintRows: the constraint system L A = E of the paper (§4): each row is sparse over the
// scene's points with a 3-vector coefficient per point, row·A = Σ_j c_jᵀ A_j. Storage is
// reused from step to step (no allocation once capacity is reached).
//
// Rows are also kept in factored form, which is what makes the solve cheap: a row is a sum of
// factors "anchor ⊗ direction",
//   L_r = Σ_f (w_f ⊗ e_f)ᵀ,   L_r·A = Σ_f Σ_j w_{f,j} e_f·A_{p_j},
// where an anchor w is a sparse combination of points (the basis values b_j(s) of a point
// constraint, b'_j(s) or b''_j(s) for tangent and curvature rows, b_j(s1) on one body and
// −b_k(s2) on another for an attachment) and e a direction in space. Since the mass matrix is
// the same on x, y and z (paper eq. 3), M⁻¹ applied to an anchor serves every row that uses it
// in any direction: a fixed point is one anchor and three directions (one scalar solve instead
// of three). Rows built term by term (addTerm/endRow) are factored per axis: up to three
// factors with e = x, y, z.
//
// Kinds of rows. Most rows are equalities (bilateral constraints, L_r A = E_r, λ_r free). Contacts
// add inequality rows (one constraint solver for both: docs/architecture.md, "One step"; Signorini's
// law, [Lenoir talk 2008]):
//   a normal row   n·(A_A − A_B) >= E_r,   λ_r >= 0,  λ_r (L_r A − E_r) = 0;
//   a friction pair t_j·(A_A − A_B) = E_r (j = 1, 2), |(λ_t1, λ_t2)| <= μ λ_n of its normal row
//     (Coulomb's disc).
// addContactRows adds them on the current anchor; the pair always follows its normal row.
//
// Guesses. A row may carry a guess of its multiplier (0 unless set): a contact's force of the
// previous step, with which an iterative solve starts (warm start).
#pragma once

#include <cassert>
#include <vector>

#include "filum/core/types.hpp"

namespace filum {

class ConstraintRows {
 public:
  enum class Kind : char { kEquality, kNormal, kFriction };

  void clear() {
    kind_.clear();
    friction_.clear();
    guess_.clear();
    inequalities_ = 0;
    start_.assign(1, 0);
    point_.clear();
    coeff_.clear();
    rhs_.clear();
    anchor_start_.clear();
    anchor_point_.clear();
    anchor_weight_.clear();
    factor_start_.assign(1, 0);
    factor_anchor_.clear();
    factor_direction_.clear();
  }

  // --- Building rows term by term (any coefficients).

  /// Adds c to the coefficient of global point p in the row being built.
  void addTerm(int p, const Vec3& c) {
    point_.push_back(p);
    coeff_.push_back(c);
  }
  /// Closes the row being built with right-hand side E_r (m/s²); factors it per axis.
  void endRow(double rhs) {
    const int first = start_.back();
    const int last = static_cast<int>(point_.size());
    for (int axis = 0; axis < 3; ++axis) {
      bool any = false;
      for (int t = first; t < last && !any; ++t) any = coeff_[t][axis] != 0.0;
      if (!any) continue;
      beginAnchor();
      for (int t = first; t < last; ++t)
        if (coeff_[t][axis] != 0.0) addAnchorPoint(point_[t], coeff_[t][axis]);
      factor_anchor_.push_back(anchors() - 1);
      factor_direction_.push_back(Vec3::Unit(axis));
    }
    closeRow(rhs);
  }

  // --- Building anchored rows: beginAnchor, addAnchorPoint..., then the rows that use it.

  /// Starts a new anchor (the current one from now on).
  void beginAnchor() { anchor_start_.push_back(static_cast<int>(anchor_point_.size())); }
  /// Adds w · (point p) to the current anchor.
  void addAnchorPoint(int p, double w) {
    anchor_point_.push_back(p);
    anchor_weight_.push_back(w);
  }
  /// Adds the row (current anchor ⊗ direction)·A = rhs. No row may be under construction.
  void addAnchoredRow(const Vec3& direction, double rhs) {
    assert(static_cast<int>(point_.size()) == start_.back() && "addTerm row not closed by endRow");
    const int a = anchors() - 1;
    for (int k = anchorBegin(a); k < anchorEnd(a); ++k) addTerm(anchor_point_[k], anchor_weight_[k] * direction);
    factor_anchor_.push_back(a);
    factor_direction_.push_back(direction);
    closeRow(rhs);
  }
  /// Adds a contact on the current anchor (+w on one side's points, −w on the other's): the
  /// normal row n·A >= rhs_n and, if μ > 0, the friction pair t1·A = rhs_1, t2·A = rhs_2 bounded
  /// by Coulomb's disc; `guess` (λ_n, λ_t1, λ_t2) their multipliers' guesses. Returns the index
  /// of the normal row.
  int addContactRows(const Vec3& n, double rhs_n, double mu, const Vec3& t1, double rhs_1, const Vec3& t2,
                     double rhs_2, const Vec3& guess = Vec3::Zero()) {
    const int normal = rows();
    addAnchoredRow(n, rhs_n);
    kind_.back() = Kind::kNormal;
    guess_.back() = guess[0];
    ++inequalities_;
    if (mu > 0.0) {
      addAnchoredRow(t1, rhs_1);
      addAnchoredRow(t2, rhs_2);
      kind_[normal + 1] = kind_[normal + 2] = Kind::kFriction;
      friction_[normal + 1] = friction_[normal + 2] = mu;
      guess_[normal + 1] = guess[1];
      guess_[normal + 2] = guess[2];
      inequalities_ += 2;
    }
    return normal;
  }

  // --- Reading rows: expanded terms.

  int rows() const { return static_cast<int>(rhs_.size()); }
  int begin(int r) const { return start_[r]; }
  int end(int r) const { return start_[r + 1]; }
  int point(int t) const { return point_[t]; }
  const Vec3& coeff(int t) const { return coeff_[t]; }
  double rhs(int r) const { return rhs_[r]; }
  Kind kind(int r) const { return kind_[r]; }
  /// μ of a friction row (its normal row is the one before the pair).
  double friction(int r) const { return friction_[r]; }
  /// The guess of row r's multiplier (0 unless the row was given one).
  double guess(int r) const { return guess_[r]; }
  /// Rows that are not equalities (contact normal and friction rows).
  int inequalityCount() const { return inequalities_; }

  /// L_r · x for a global vector x (3N points first).
  double dot(int r, const VecX& x) const {
    double sum = 0.0;
    for (int t = start_[r]; t < start_[r + 1]; ++t) sum += coeff_[t].dot(x.segment<3>(3 * point_[t]));
    return sum;
  }
  /// x += w L_rᵀ.
  void addTransposed(int r, double w, VecX& x) const {
    for (int t = start_[r]; t < start_[r + 1]; ++t) x.segment<3>(3 * point_[t]) += w * coeff_[t];
  }

  // --- Reading rows: factors and anchors.

  int anchors() const { return static_cast<int>(anchor_start_.size()); }
  int anchorBegin(int a) const { return anchor_start_[a]; }
  int anchorEnd(int a) const {
    return a + 1 < anchors() ? anchor_start_[a + 1] : static_cast<int>(anchor_point_.size());
  }
  int anchorPoint(int k) const { return anchor_point_[k]; }
  double anchorWeight(int k) const { return anchor_weight_[k]; }

  int factorBegin(int r) const { return factor_start_[r]; }
  int factorEnd(int r) const { return factor_start_[r + 1]; }
  int factorAnchor(int f) const { return factor_anchor_[f]; }
  const Vec3& factorDirection(int f) const { return factor_direction_[f]; }

 private:
  void closeRow(double rhs) {
    start_.push_back(static_cast<int>(point_.size()));
    factor_start_.push_back(static_cast<int>(factor_anchor_.size()));
    rhs_.push_back(rhs);
    kind_.push_back(Kind::kEquality);
    friction_.push_back(0.0);
    guess_.push_back(0.0);
  }

  // Expanded terms: row r holds terms [start_[r], start_[r+1]).
  std::vector<int> start_{0};
  std::vector<int> point_;
  std::vector<Vec3> coeff_;
  std::vector<double> rhs_;
  std::vector<Kind> kind_;
  std::vector<double> friction_;  // μ of friction rows, 0 elsewhere
  std::vector<double> guess_;     // guesses of the multipliers, 0 unless given
  int inequalities_ = 0;
  // Anchors: anchor a holds points [anchor_start_[a], anchor_start_[a+1]).
  std::vector<int> anchor_start_;
  std::vector<int> anchor_point_;
  std::vector<double> anchor_weight_;
  // Factors: row r holds factors [factor_start_[r], factor_start_[r+1]).
  std::vector<int> factor_start_{0};
  std::vector<int> factor_anchor_;
  std::vector<Vec3> factor_direction_;
};

}  // namespace filum
