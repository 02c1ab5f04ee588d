// ContactNewton: the frictional contact problem of one constraint solve, solved by a semismooth
// Newton method on the Alart–Curnier function (P. Alart, A. Curnier, "A mixed formulation for
// frictional contact problems prone to Newton like solution methods", CMAME 92 (1991) 353; the
// same function Siconos' fc3d_nonsmooth_Newton_AlartCurnier solves), damped by a line search.
//
// The problem (lagrange_multiplier_solver.hpp): W λ − β = w, with W = L A⁻¹ Lᵀ symmetric positive
// semi-definite, and per row kind
//   equality rows:  w_r = 0;
//   normal rows:    0 <= λ_n ⊥ w_n >= 0                              (Signorini);
//   friction pairs: λ_t in the disc D(μ λ_n), w_t = 0 inside it, and on its rim λ_t opposes
//                   w_t: λ_t = −μ λ_n w_t/|w_t|                       (Coulomb, maximal dissipation).
// Alart–Curnier writes all three as one equation F(λ) = λ − P(λ − ρ w(λ)) = 0 with P the
// projection on the admissible set:
//   equality:  P(z) = z, so F_r = ρ_r w_r;
//   normal:    F_n = λ_n − max(0, z_n),              z_n = λ_n − ρ_n w_n;
//   friction:  F_t = λ_t − proj_{D(μ max(0, z_n))}(z_t),  z_t = λ_t − ρ_t w_t.
// ρ_r = 1/W_rr (ρ_t = 2/(W_t1t1 + W_t2t2) for both rows of a pair: the disc stays a disc). F = 0
// is exactly the true (non-convex) Coulomb problem: sticking contacts have w_t = 0, no creep.
//
// Newton. F is piecewise smooth; its generalized Jacobian J = I − D (I − ρ W), D the Jacobian of
// P at z (1 on equality rows, active normal rows and sticking pairs; 0 on inactive rows;
// (R/|z_t|)(I − ẑẑᵀ) and μ ẑ ∂z_n on a sliding pair, R = μ z_n). Rows with D = 0 have the step
// Δ_r = −λ_r; the rest form a smaller system J_SS Δ_S = −F_S − J_SI Δ_I, solved by a dense LU
// with partial pivoting (J is not symmetric on sliding pairs) or through A's band (the cost
// paragraph below). Redundant contacts (spheres every
// 0.3 mm on a thread of 1 mm spans) make W nearly singular (cond ~1e10), so J_SS is shifted by
// δ I, rows of J_SS being scaled to a unit diagonal by ρ: a Levenberg–Marquardt step with δ the
// relative residual, clamped to [damping, max_damping] (Yamashita & Fukushima 2001: δ_k ~ |F_k|
// keeps the local quadratic rate). Far from the solution it holds back the steps along the
// near-null directions of redundant rows; it does not move the solution — F is unchanged.
// A step is accepted by a non-monotone Armijo test (Grippo, Lampariello & Lucidi 1986) on
// θ = Σ_r (F_r/ρ_r)² against the largest of the last 8 merits, halving it up to 30 times. Short
// steps are normal while the active set is still being found (contacts opening, pairs starting to
// slide, where F has kinks): Newton goes on through them. Only a step cut below stall_step (2⁻¹⁶)
// stops the solve as stalled, and the caller (the constraint solver) smooths λ by a few projected
// Gauss–Seidel sweeps before it calls Newton again. Measured (bench_realtime, the knot and the
// capstan sliding): stopping already below 1/64, as this solver first did, and smoothing there
// undid Newton's progress — 96.1 % and 94.4 % of their solves converged against 100 % and 98.5 %
// at 2⁻¹⁶, and the sliding capstan cost 2.9 against 1.6 ms per simulated ms.
//
// Stop. The residual is max_r |F_r|/ρ_r (m/s²): the largest violation of complementarity, of the
// disc or of stick, as an acceleration; the solve stops when it is below tolerance times the
// largest term it balances, max(|β|∞, max_r |λ_r|(W_rr + R_r)) — the round-off of (W + R)λ − β is
// of that size, and in a tight knot the contact forces exceed the right-hand side by orders.
//
// Cost per iteration: (W + R) Δ (c², one product for all the line search's trials); J's rows as forms in terms of W's rows (O(c): at most three W
// rows and three unit terms each, not c² entries); the right-hand side's W Δ_I (a column of W per
// free row that moves); and the step's linear system J_SS Δ_S = r on the |S| rows that are not
// free: by a dense LU (3 |S|² to form it from the forms, |S|³/3 to factor it), or — given the
// matrix A that W was formed with (Structure) — through A's band and the rows' sparsity without
// W (AugmentedNewtonSystem: Σ envelope² multiply-adds, a few hundred per row against an
// obstacle), whichever is cheaper — or, on a chord step (below), a substitution on the factors
// held from an earlier iteration. With the Structure the products with W are also taken as
// L (A⁻¹ (Lᵀ x)) — the rows' forces on their points, a band solve per body, the rows' reading of
// the response: O(terms + Σ_b groups_b · range_b) against c² — when that is cheaper (many rows
// on few points: a wire lying along a catheter, a rod on a table) — BandDelassusProduct. Then W
// itself is asked for (DelassusEntries) only by a dense LU step, so a caller may leave it unformed
// until then: a solve whose every step goes through the band never forms W.
//
// Chord steps. J_SS changes with λ only through the active set (which rows are tied, sliding or
// free) and, on sliding pairs, through the slip direction ẑ and R/|z_t|; with the same W and the
// same active set, the last factorization is J_SS at a nearby iterate. A step may then be taken
// on it (a chord step: Newton's simplified iteration, Ortega & Rheinboldt 1970 §7.1; Hairer &
// Wanner's stiff solvers keep their Jacobian the same way): one substitution instead of a
// factorization, exact where only tied rows are solved (their forms are ρ_r W_r + ρ_r R_r e_r,
// constant; up to the Levenberg shift δ, which moves with the residual), a step that contracts
// the error linearly where pairs slide. It is taken whole, and only when it divides |F| by 4 at
// least (kChordContraction, in contact_newton.cpp with what was measured); otherwise it is
// discarded and the iteration is taken by Newton on a fresh factorization, so a chord step is
// never a poor one. A factorization serves chords only from Newton's local phase: one whose own
// step the line search had to cut (the active set still moving) is not kept. The factorization
// is carried from one solve to the next only under the same Settings::matrix_key (the linearized
// implicit step and its error estimate: two solves on one W, whose right-hand sides differ by the
// estimate's correction).
// The workspace only grows: a steady step allocates nothing.
#pragma once

#include <algorithm>
#include <vector>

#include "filum/constraints/augmented_newton_system.hpp"
#include "filum/constraints/band_delassus_product.hpp"
#include "filum/core/block_inverse.hpp"
#include "filum/core/constraint_problem.hpp"
#include "filum/core/constraint_rows.hpp"
#include "filum/core/types.hpp"

namespace filum::constraints {

/// W (c × c, both triangles) for a solve that may not need it: formed by its owner when first
/// asked, and then valid for the rest of the solve.
class DelassusEntries {
 public:
  virtual const MatX& matrix() = 0;
  /// Whether matrix() costs nothing more: W is formed already.
  virtual bool formed() const = 0;

 protected:
  ~DelassusEntries() = default;
};

class ContactNewton {
 public:
  struct Settings {
    int iterations = 50;     // Newton iterations at most
    double damping = 1e-9;      // δ's floor, the proximal shift of J_SS (its rows have a unit diagonal)
    double max_damping = 1.0;   // δ's ceiling (δ follows the relative residual in between)
    double stall_step = 1.0 / 65536;  // a line search that had to cut the step below this stops the solve
    bool structured = true;  // the step's system and W's products through A's band when cheaper (false: dense always)
    // The caller's name for W, its compliance and the rows (>= 0): a solve that passes the key of
    // the previous solve says they are the same, and that solve's last factorization of J_SS may
    // serve its steps (chord steps, below). −1: not known to be the same (nothing carried over).
    long matrix_key = -1;
    bool chords = true;  // chord steps on the held factorization (false: one factorization per iteration)
  };
  /// What a structured step needs besides W: the matrix A that W = L A⁻¹ Lᵀ was formed with, the
  /// bodies, and the body of each point; and, optionally, W's band product already prepared on
  /// these rows by the caller (null: prepared here from the rest).
  struct Structure {
    const BlockInverse* inverse = nullptr;
    const ConstraintProblem* problem = nullptr;
    const std::vector<int>* point_body = nullptr;
    BandDelassusProduct* product = nullptr;
  };
  struct Result {
    int iterations = 0;
    double residual = 0.0;   // max_r |F_r|/ρ_r at the returned λ (m/s²)
    bool converged = false;  // residual <= threshold
    bool stalled = false;    // stopped on a short step (stall_step)
    double threshold = 0.0;  // tolerance · max(|β|∞, max_r |λ_r| (W_rr + R_r)) at the returned λ
    int structured_steps = 0;  // Newton steps solved through A's band, chords on its factors included (the rest: dense LU)
    int chord_steps = 0;       // steps taken on an earlier factorization (chord steps, kept)
  };

  /// Solves for λ (in: the warm start; out: the last iterate, or the best one when it did not
  /// converge). `w` is W with both triangles (c × c leading block), `beta` β, `rows` the kinds.
  /// W is the leading c × c block of `w` (c = β's size), with both triangles; `compliance` R
  /// (one per row, >= 0) makes the problem that of W + diag(R).
  /// With `structure` (not null) the steps may be solved through A's band (Settings::structured).
  Result solve(const MatX& w, const Eigen::Ref<const VecX>& beta, const Eigen::Ref<const VecX>& compliance,
               const ConstraintRows& rows, const Settings& settings, double tolerance, Eigen::Ref<VecX> lambda,
               const Structure* structure = nullptr);
  /// The same with W formed only if a step needs its entries (w.matrix(): a dense LU step, or
  /// products when the band's are not cheaper); `w_diagonal` is W's diagonal (c values).
  Result solve(DelassusEntries& w, const Eigen::Ref<const VecX>& w_diagonal, const Eigen::Ref<const VecX>& beta,
               const Eigen::Ref<const VecX>& compliance, const ConstraintRows& rows, const Settings& settings,
               double tolerance, Eigen::Ref<VecX> lambda, const Structure* structure = nullptr);

  /// W λ of the λ the last solve returned (c values): the product its last measure of the
  /// residual took, which is always λ's own (solve's exit measures the iterate it returns).
  Eigen::Ref<const VecX> lastProduct() const { return w_lambda_.head(c_); }

  /// max_r |F_r|/ρ_r (m/s²) of λ, given the diagonal of W + R and (W + R)λ − β: the residual by which any
  /// contact solve (projected Gauss–Seidel too) is measured.
  double residual(const ConstraintRows& rows, const Eigen::Ref<const VecX>& diagonal, const Eigen::Ref<const VecX>& wl,
                  const Eigen::Ref<const VecX>& lambda);

 private:
  /// Workspace for c rows (grows only).
  void grow(int c);
  /// ρ per row (from W's diagonal).
  void scale(const Eigen::Ref<const VecX>& diagonal, const ConstraintRows& rows);
  /// F and the merit θ at λ, given wl_ = (W + R)λ − β; with `jacobian`, J's rows as forms (forms_:
  /// Σ b_k W_k + Σ c_m e_m, three of each at most) and the free set.
  double evaluate(bool jacobian, const ConstraintRows& rows, const Eigen::Ref<const VecX>& lambda);
  /// Δ from J Δ = −F (the reduced system). With `chord`, on the held factorization when it fits
  /// the solved rows (chord_taken_ says so); step_structured_: solved through A's band.
  bool step(double damping, const ConstraintRows& rows, bool chord);
  /// Whether the held factorization is of J_SS on the same solved rows, each of the same kind
  /// (tied or sliding: the forms' pattern).
  bool heldFits() const;
  /// Records the solved rows and their kinds of the factorization just made.
  void hold(bool structured);
  /// J_SS Δ_S = rhs_ through A's band (AugmentedNewtonSystem), when structure_ allows it and it
  /// costs less than the dense LU; false: not taken (or refused), the dense LU is used.
  bool structuredStep(double damping, const ConstraintRows& rows);
  /// J_SS + δ I into lu_ from the forms (the dense step).
  void denseSystem(int s, double damping);
  /// Whether products with W go through A's band in this solve (product_), by their cost.
  void chooseProduct(const ConstraintRows& rows);
  /// W dense, asked of entries_ the first time in a solve.
  const MatX& matrix();
  /// out := W x (c values), by W or through A's band.
  void multiplyW(const ConstraintRows& rows, const Eigen::Ref<const VecX>& x, Eigen::Ref<VecX> out);
  /// In-place LU with partial pivoting of lu_'s leading s × s block; false if singular.
  bool factor(int s);
  void substitute(int s, Eigen::Ref<VecX> x) const;

  int c_ = 0;
  VecX rho_, wl_, f_, delta_, trial_, best_, rhs_, compliance_, diagonal_;
  int capacity_ = 0;
  MatX lu_;    // J_SS + δ I (dense step), factored in place
  VecX w_free_;  // W Δ_I: the free rows' steps seen by W's rows
  VecX wl_base_, w_delta_;  // (W + R)λ − β at the line search's start, and (W + R)Δ
  VecX w_lambda_;  // W λ of the last exact measure (lastProduct)
  DelassusEntries* entries_ = nullptr;  // W of the current solve, formed when asked
  const MatX* w_matrix_ = nullptr;      // W once asked (null: not yet)
  std::vector<int> solved_, free_, pivot_;
  std::vector<char> is_free_;
  std::vector<NewtonRowForm> forms_;  // J's rows in terms of W's rows (evaluate, with the Jacobian)
  std::vector<int> row_position_;     // row → its index in solved_ (−1: free)
  const Structure* structure_ = nullptr;
  bool structured_ = true;
  BandDelassusProduct* product_ = nullptr;  // W x as L A⁻¹ Lᵀ x in this solve (chooseProduct; null: W's)
  BandDelassusProduct own_product_;         // prepared here when the Structure brings none
  VecX formed_diagonal_;                    // W's diagonal, contiguous (solve with W formed)
  AugmentedNewtonSystem augmented_;
  // The last factorization of J_SS + δ I (lu_, or augmented_ when held_structured_), for chord
  // steps: valid while held_, for W named held_key_, on the rows held_solved_ with the forms'
  // pattern held_pattern_ (nb per solved row).
  bool held_ = false;
  bool held_structured_ = false;
  long held_key_ = -1;
  std::vector<int> held_solved_;
  std::vector<int> held_pattern_;
  bool chord_taken_ = false;      // the last step() was a chord step
  bool step_structured_ = false;  // the last step() was solved through A's band
  double max_abs_residual_ = 0.0;
  double force_scale_ = 0.0;  // max_r |λ_r|/ρ_r of the last evaluation (m/s²)

 public:
  /// max_r |λ_r| (W_rr + R_r) of the last evaluation (solve or residual): with |β|∞ the scale
  /// a residual is measured against.
  double forceScale() const { return force_scale_; }
  /// The residual asked for: tolerance · max(|β|∞, forceScale()) (m/s²).
  double threshold(double tolerance, double beta_scale) const {
    return tolerance * std::max({beta_scale, force_scale_, 1e-300});
  }
};

}  // namespace filum::constraints
