// LagrangeMultiplierSolver: the constraint solver of a scene — bilateral constraints of every
// body and unilateral contacts with Coulomb friction together, on one Delassus operator, by the
// acceleration decomposition (paper §4, [Lenoir talk 2008] "fallopian tubes"):
//   M A_t = B                       (tendency acceleration, done by the scene)
//   W λ = E − L A_t,  W = L M⁻¹ Lᵀ  (c × c Delassus system)
//   A = A_t + M⁻¹ Lᵀ λ
// M is block diagonal (one block per body), given as a BlockInverse: the mass matrices for
// explicit steps, the step matrix M − h D − h² K for implicit ones.
//
// Cost. Rows come factored as anchor ⊗ direction (constraint_rows.hpp): an anchor touches the
// d + 1 control points whose basis is non-zero at its abscissa (4 for a cubic B-spline), on one
// body or two. When the operator is the mass matrix (BlockInverse::sameOnEveryAxis):
//   - y_a = M_b⁻¹ w_a is one *scalar* band solve per anchor and body, O(n_b), and three anchors
//     share one 3-column solve (x, y, z columns) — a fixed point's 3 rows cost a third of one
//     3-column solve instead of three;
//   - G_ab = w_aᵀ y_b (O(d)), W_rk = Σ G_ab (e_r·e_k) for the factors of rows r, k (O(1) per
//     entry, symmetric: the lower triangle only);
//   - A += M⁻¹ (Lᵀ λ): scatter Lᵀλ (O(c d)), one band solve per touched body (O(n));
//   - y_a is kept from one call to the next while the anchor (points and weights) and the
//     operator (BlockInverse::revision) are unchanged; anchors that move (a sliding point) are
//     solved again. When every anchor and every row direction is as in the previous call, W is
//     the same matrix: its assembly and factorization are skipped too, and the call costs the
//     right-hand side, one back-substitution and the final band solve — O(c d + c² + n) dense,
//     O(c d + nnz + n) sparse.
// Total O(a·n + c² + factorization), a <= c anchors, against the paper's O(c n² + c² n + c³).
// For other operators (implicit steps mix the coordinates) each row gets its own 3-column
// solve over the bodies it touches (O(c·n)), or a whole-scene solve if the operator couples
// bodies; the columns are kept while the operator (its revision) and the rows are unchanged.
// With contacts by Newton, W may instead come from A⁻¹'s blocks between the rows' points
// (point_inverse_blocks.hpp), kept while the operator is.
//
// The c × c system. Up to `sparse_above` rows (default 64) W is factored densely (LDLᵀ with
// pivoting, O(c³), negligible at that size). Above, it goes to a sparse LDLᵀ: SuiteSparse
// CHOLMOD when built with FILUM_WITH_SUITESPARSE, else Eigen's SimplicialLDLT (AMD ordering).
// The factorization is kept while W is unchanged (bit for bit).
//
// How sparse W really is. Between bodies, W is exactly block sparse: rows on different bodies
// do not couple unless a junction or an attachment joins them. Within one body it is dense in
// exact arithmetic — M⁻¹ is a full matrix — but its entries decay geometrically with the
// distance between the anchors: for the uniform cubic B-spline mass matrix, (M⁻¹)_ij falls like
// ρ^|i−j| with ρ ≈ 0.5352 per control point (the largest root of modulus < 1 of the degree-7
// Euler–Frobenius polynomial, the symbol of the B-spline Gram matrix; measured in
// tests/constraints/lagrange_multiplier_solver_test.cpp). So beyond ~60 control points
// (measured (M⁻¹)_{j,j+60} / (M⁻¹)_jj ≈ 6e-17) W_rk is below double-precision round-off of W_rr. The sparse path drops
// |W_rk| <= τ √(W_rr W_kk) (τ = `drop_tolerance`, default 1e-14): with τ at round-off level
// the dropped part is of the size of the rounding errors already in W, and λ agrees with the
// dense solution to about cond(W)·τ (tested). W is then banded along each thread, with a band
// set by how many anchors lie within ~57 control points of each other: truly sparse for
// constraints far apart on long threads, dense (and no cheaper) for many constraints on a
// short one. τ = 0 keeps every entry (exact, sparse only across bodies).
//
// Contacts (ConstraintRows::Kind; the rows are built by collision/contact_pipeline.hpp). With
// inequality rows the same W and β = E − L A_t give a mixed complementarity problem ([Lenoir talk 2008],
// catheter: "Signorini's law 0 <= d ⊥ f >= 0 ... Delassus operator W = H C Hᵀ"):
//   equality rows B:  (W λ − β)_B = 0,                   λ_B free;
//   normal rows:      (W λ − β)_n >= 0, λ_n >= 0,         λ_n (W λ − β)_n = 0;
//   friction pairs:   (W λ − β)_t = 0 inside the disc    |(λ_t1, λ_t2)| <= μ λ_n.
// Solved by a semismooth Newton method on the Alart–Curnier function (contact_newton.hpp) on W
// kept dense (up to newton_rows rows; the Gauss–Seidel operators below are then not used): it
// converges on the nearly singular W of a tight knot, where projected Gauss–Seidel plateaus
// (docs/contact-solver.md has the measurements), and it stops on the true residual. λ starts from
// the previous call's when the rows are of the same kinds (the stages of one step), else from the
// rows' guesses (the last step's contact forces). When Newton does not reach the threshold in
// newton_iterations, projected Gauss–Seidel continues from its best iterate and the statistics say
// so (fell_back); Statistics::residual is what was reached either way.
// Projected block Gauss–Seidel ("contact_method": "gauss_seidel", the fallback, and the method
// above newton_rows): each sweep solves the equality block exactly,
// Δλ_B = W_BB⁻¹ (β − W λ)_B (W_BB factored once per call by LDLᵀ), then every contact row in
// order, λ_r ← proj(λ_r + (β − W λ)_r / W_rr), a friction pair projected on its disc after both
// rows moved. With the disc's radius μ λ_n moving with λ_n the problem is not a convex one and
// Gauss–Seidel has no convergence guarantee; on redundant contacts (more rows than the strands'
// degrees of freedom) it slows to a crawl. It stops when the Alart–Curnier residual is below
// contact_tolerance · |β|∞ (checked when a sweep changed no row's acceleration by more than that,
// W_rr |Δλ_r|, and every 8 sweeps) or after contact_iterations sweeps. W is the matrix assembled
// above (dense or sparse, kept while unchanged — within a step the contact set and its anchors are
// fixed), or through an implicit step matrix its factored form; a sweep costs O(nnz(W)).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Cholesky>

#include "filum/constraints/augmented_newton_system.hpp"
#include "filum/constraints/band_delassus_product.hpp"
#include "filum/constraints/contact_newton.hpp"
#include "filum/constraints/point_inverse_blocks.hpp"
#include "filum/core/constraint_solver.hpp"
#include "filum/core/params.hpp"

namespace filum::constraints {

class LagrangeMultiplierSolver final : public ConstraintSolver {
 public:
  enum class SparseBackend { kCholmod, kSimplicialLdlt };
  /// The Delassus operator of the contact sweeps through an operator that mixes the axes:
  /// whichever costs less per sweep, W assembled, or factored (A⁻¹Lᵀλ kept, W never assembled).
  enum class ContactForm { kAuto, kAssembled, kFactored };
  /// How rows with contacts are solved: semismooth Newton on the Alart–Curnier function
  /// (contact_newton.hpp; projected Gauss–Seidel only as its fallback), or projected Gauss–Seidel.
  enum class ContactMethod { kNewton, kGaussSeidel };

  struct Options {
    int sparse_above = 64;          // c above this: sparse factorization of W
    double drop_tolerance = 1e-14;  // sparse path: drop |W_rk| <= τ √(W_rr W_kk)
    bool reuse = true;              // keep M⁻¹ w_a for unchanged anchors between calls
    ContactMethod contact_method = ContactMethod::kNewton;
    int newton_iterations = 100;    // Newton iterations at most (contact rows; measured: 50 left 1.5 % of the
                                    // sliding capstan's solves to the costlier Gauss–Seidel fallback, 100 none)
    double newton_damping = 1e-9;   // floor of ContactNewton's shift δ (its rows have a unit diagonal)
    int newton_presweeps = 0;       // Gauss–Seidel sweeps on the warm start before Newton, W formed: its
                                    // active set corrected by projection (docs/contact-solver.md: knot.json
                                    // sets 2, 14 → 11 Newton iterations a solve; not the default, as under a
                                    // full Newton integrator the sweeps' pick among redundant rows changes from
                                    // one iteration to the next and a stiff scene failed to converge)
    int newton_rows = 2000;         // Newton on W kept dense up to this many rows; above, Gauss–Seidel
    bool newton_structured = true;  // Newton's steps through A's band when cheaper (ContactNewton::Structure)
    bool newton_chords = true;      // chord steps on the last factorization (ContactNewton::Settings::chords)
    bool point_blocks = true;       // Newton's W from A⁻¹'s blocks between touched points when cheaper (point_inverse_blocks.hpp)
    double contact_compliance = 1e-6;   // ε_n: R = ε_n W_rr on normal rows
    double friction_compliance = 1e-6;  // ε_t: R = ε_t W_rr on friction rows
    int contact_iterations = 200;   // projected Gauss–Seidel sweeps at most (contact rows)
    double contact_tolerance = 1e-6;  // on the Alart–Curnier residual, relative (see Statistics::threshold)
    ContactForm contact_form = ContactForm::kAuto;
    SparseBackend backend = cholmodAvailable() ? SparseBackend::kCholmod : SparseBackend::kSimplicialLdlt;
  };

  /// What the last solve did (benchmarks and tests; not part of the physics).
  struct Statistics {
    int rows = 0;            // c
    int columns = 0;         // anchors (mass operator) or rows (other operators)
    int solved_columns = 0;  // columns whose M⁻¹ was computed in this call
    int reused_columns = 0;  // columns kept from the previous call
    long nonzeros = 0;       // entries of W's lower triangle that were kept
    bool sparse = false;     // sparse factorization used
    bool refactored = false; // W changed and was factored again
    bool reassembled = false;  // W was assembled (false: unchanged anchors and directions, or never asked for: deferred)
    bool deferred = false;   // W left unformed until the contact Newton asks for it (its products through the band)
    int far_rows = 0;        // deferred: rows whose W_rr took a solve, their points further apart than the range taken
    int inverse_range = 0;   // deferred: the widest range of A⁻¹'s blocks taken on a body (>= its band's)
    int inequalities = 0;    // contact rows (normal and friction)
    int sweeps = 0;          // projected Gauss–Seidel sweeps (with contact rows; smoothing and fallback included)
    double change = 0.0;     // the last sweep's largest W_rr |Δλ_r| (m/s²)
    int newton_iterations = 0;  // Newton iterations (with contact rows, method newton)
    double residual = 0.0;   // Alart–Curnier residual max_r |F_r|/ρ_r of the returned λ (m/s²)
    double threshold = 0.0;  // the residual asked for: contact_tolerance · max(|β|∞, max_r |λ_r|(W_rr + R_r)) (m/s²)
    bool converged = true;   // residual <= threshold (always true without contact rows)
    bool fell_back = false;  // Newton did not converge and projected Gauss–Seidel took over
    int structured_steps = 0;  // Newton steps solved through A's band, chords on its factors included (the others by a dense LU)
    int chord_steps = 0;       // Newton steps on an earlier factorization (contact_newton.hpp, chord steps)
    bool point_blocks = false;  // W formed from A⁻¹'s blocks between touched points (not from per-row columns)
    int point_columns = 0;      // columns A⁻¹ E_p solved for points newly touched (3 per point)
    bool equality_band = false;  // equality rows only, solved through A's band (W never formed)
    bool equality_block_band = false;  // with contacts: W_BB⁻¹ (the equality rows' steps) through A's band
    int block_products = 0;     // deferred: W_BB's columns by band products (0: from A⁻¹'s band, or held)
    bool held = false;          // deferred: W's diagonal kept from the last call on the same W (the estimate)
    bool block_held = false;    // deferred: W_BB and its factors kept from the last call on the same W
  };

  LagrangeMultiplierSolver();
  explicit LagrangeMultiplierSolver(Options options);
  ~LagrangeMultiplierSolver() override;

  /// "sparse_above": c threshold (integer >= 0, default 64), "drop_tolerance": τ in [0, 1e-6]
  /// (default 1e-14), "reuse": bool (default true), "sparse_solver": "cholmod" (default when
  /// built with FILUM_WITH_SUITESPARSE) or "simplicial_ldlt"; with contacts "contact_method"
  /// ("newton", default, or "gauss_seidel"), "newton_iterations" (default 100), "newton_damping"
  /// (the floor of Newton's shift δ, in [0, 1e-3], default 1e-9), "newton_linear_solve" ("auto",
  /// default: each step's system through the step matrix's band when that is cheaper, or "dense":
  /// always a dense LU; the same steps up to round-off), "newton_chord_steps" (default true: steps on
  /// the last factorization of the step's system while they contract, within a solve and between
  /// the solves of one step on the same W; false: a factorization per Newton iteration; the same
  /// solution to the tolerance), "point_blocks" (default true: W from A⁻¹'s
  /// blocks between the rows' points, kept while A is, when that takes fewer multiply-adds than a
  /// column per row; false: always a column per row), "contact_compliance" and
  /// "friction_compliance" (ε in [0, 1], default 1e-6), "newton_rows" (default 2000),
  /// "contact_iterations" (Gauss–Seidel sweeps, default 200), "contact_tolerance" (relative,
  /// default 1e-6) and
  /// "contact_form" ("auto", "assembled", "factored": Gauss–Seidel's operator; the same solution
  /// up to round-off, at different costs).
  static std::unique_ptr<LagrangeMultiplierSolver> fromParams(const Params& p);
  static bool cholmodAvailable();

  std::string typeName() const override { return "LagrangeMultiplierSolver"; }
  void solve(const ConstraintProblem& problem, const ConstraintRows& rows, const BlockInverse& inverse, VecX& a) override;

  /// Multipliers of the last solve (N for a fixed point: the force holding it).
  Eigen::Ref<const VecX> multipliers() const override { return lambda_.head(c_); }
  /// λ of the last call and its rows' kinds: the warm start of the next call (warmStart).
  void saveMemory(StepMemory& memory) const override;
  void restoreMemory(const StepMemory& memory) override;
  /// Drops the contact Newton's factorization carried between the solves of a step.
  void beginStep() override { step_began_ = true; }
  const Statistics& statistics() const { return stats_; }
  /// W_rr of the last solve's rows, as its ρ and compliance were set from (tests).
  Eigen::Ref<const VecX> delassusDiagonal() const { return diagonal_.head(c_); }
  const Options& options() const { return options_; }

 private:
  /// A⁻¹ applied to one anchor (width 1: one value per point) or to one row (width 3), kept
  /// only on the bodies it touches: segment i, of body bodies[i], starts at y[starts[i]].
  struct Column {
    std::uint64_t hash = 0;
    std::vector<int> points;     // anchor content (width 1), to recognise it next call
    std::vector<double> weights;
    std::vector<int> bodies, starts;
    VecX y;
    bool ready = false;  // y computed (or taken over) in this call
    bool taken = false;  // (previous call's columns) y handed over already
    int from = -1;       // index of the previous call's column it was taken from
  };
  struct SparseFactor;

  void prepareColumns(const ConstraintProblem& problem, const ConstraintRows& rows, const BlockInverse& inverse, bool separable);
  void layoutColumn(const ConstraintProblem& problem, Column& column, int width) const;
  void assembleSeparable(const ConstraintProblem& problem, const ConstraintRows& rows);
  void assembleGeneral(const ConstraintProblem& problem, const ConstraintRows& rows);
  /// W dense by column axpys when every column lives on the same bodies; false: not taken.
  bool assembleGeneralByColumns(const ConstraintProblem& problem, const ConstraintRows& rows);
  void storeEntry(int r, int k, double value);
  /// W dense from A⁻¹'s blocks between the rows' points (point_blocks_, all held).
  void assembleFromPointBlocks(const ConstraintRows& rows);
  /// a += A⁻¹ Lᵀ λ by scattering Lᵀ λ and one solve per touched body.
  void scatterForces(const ConstraintProblem& problem, const ConstraintRows& rows, const BlockInverse& inverse, VecX& a);
  void factorAndSolve();
  /// Equality rows only, through an operator with a band (an implicit step's matrix): λ from the
  /// augmented system [A −Lᵀ; L 0] [u; λ] = [0; E − L a_t] by its envelope LU
  /// (augmented_newton_system.hpp, every row's form W_r), when that costs fewer multiply-adds than
  /// the column per row W would be formed from. False (nothing done) otherwise.
  bool solveEqualitiesThroughBand(const ConstraintProblem& problem, const ConstraintRows& rows,
                                  const BlockInverse& inverse, const VecX& a);
  /// W as full symmetric rows (adjacency_), from the dense or sparse lower triangle.
  void buildAdjacency(int c);
  /// (W λ)_r.
  double delassusRow(int r) const;
  /// λ with contact rows by projected Gauss–Seidel (see above) on a Delassus operator: W
  /// assembled (AssembledDelassus) or in factored form (FactoredDelassus).
  struct AssembledDelassus;
  struct DenseDelassus;
  struct FactoredDelassus;
  struct BandProductDelassus;
  class DeferredDelassus;
  template <class Delassus>
  void solveWithContacts(const ConstraintRows& rows, Delassus& w);
  void solveWithNewton(const ConstraintProblem& problem, const ConstraintRows& rows, const BlockInverse& inverse,
                       bool deferred);
  /// Where this call's W comes from: per-row columns A⁻¹ l_r, A⁻¹'s blocks between the rows'
  /// points (point_blocks_), or — W deferred — A⁻¹'s blocks within each body's band (its diagonal
  /// only; columns are solved if W is formed after all).
  enum class DelassusSource { kColumns, kPointBlocks, kInverseBand };
  /// W_rr from this call's source.
  double diagonalEntry(const ConstraintProblem& problem, const ConstraintRows& rows, int r) const;
  /// W_rk = Σ_{t ∈ r} Σ_{t' ∈ k} c_tᵀ H(p_t, p_t') c_t' from A⁻¹'s point blocks (all held).
  double pointBlockEntry(const ConstraintRows& rows, int r, int k) const;
  /// W_rr = Σ_{t, t' ∈ r} c_tᵀ (A⁻¹)(p_t, p_t') c_t' from the inverse bands (inverseBandCovers),
  /// or for a far row (its points further apart on a body than the band) from its solve.
  double inverseBandDiagonal(const ConstraintRows& rows, int r) const;
  /// W_rk from the inverse bands into `entry`; false when two of the rows' points on a body lie
  /// further apart than the range taken on it (inverseBandCovers and computeInverseBands ran).
  bool inverseBandEntry(const ConstraintRows& rows, int r, int k, double& entry) const;
  /// Whether W's diagonal comes from the bands: every body the rows touch has a band, and the far
  /// rows (far_row_: a body touching itself far along it, as a bowel lying in loops) are at most
  /// three times the rows' distinct points — each costs a band solve, where W from A⁻¹'s point
  /// blocks would take three per point and the columns one per row (body_touched_,
  /// inverse_band_layout_ and problem_offset_ set).
  bool inverseBandCovers(const ConstraintProblem& problem, const ConstraintRows& rows, const BlockInverse& inverse);
  /// visit(body, span) for each body row r acts on: the widest distance between two of its
  /// points on that body in the band's groups (inverse_band_layout_ and problem_offset_ set).
  template <class Visit>
  void forEachRowSpan(const ConstraintRows& rows, int r, Visit&& visit) const;
  /// A⁻¹'s blocks within the range taken on every touched body (inverse_band_, inverse_range_),
  /// and each far row's W_rr = l_r · A⁻¹ l_r by a solve (far_diagonal_), after inverseBandCovers.
  void computeInverseBands(const ConstraintProblem& problem, const ConstraintRows& rows, const BlockInverse& inverse);
  /// Whether W comes from A⁻¹'s blocks between the rows' points (point_blocks_, brought up to
  /// date then) rather than a column per row: by their multiply-adds with nothing held (solve()).
  bool choosePointBlocks(const ConstraintProblem& problem, const ConstraintRows& rows, const BlockInverse& inverse);
  /// W formed (lower triangle, as step 2 forms it) unless w_ holds it already (!w_unformed_).
  void formDelassus(const ConstraintProblem& problem, const ConstraintRows& rows, const BlockInverse& inverse);
  /// The equality rows solved exactly for the current contact forces (after an iterative solve).
  template <class Delassus>
  void polishEqualities(const ConstraintRows& rows, Delassus& w);
  /// The equality rows and their block W_BB, factored (once per solve).
  template <class Delassus>
  void factorEqualityBlock(const ConstraintRows& rows, Delassus& w, const ConstraintProblem* problem = nullptr,
                           const BlockInverse* inverse = nullptr);
  /// The augmented system of the rows `solved` (each form W_r) laid out and factored in
  /// equality_system_, when its envelope LU is cheaper than a band solve per row and `dense_cost`;
  /// false (nothing kept) otherwise.
  bool buildEqualitySystem(const ConstraintRows& rows, const std::vector<int>& solved, const ConstraintProblem& problem,
                           const BlockInverse& inverse, double dense_cost);
  /// λ_B += W_BB⁻¹ (β − Wλ)_B; returns the largest change of a row's acceleration (m/s²).
  template <class Delassus>
  double equalityStep(Delassus& w);
  /// λ from the previous call (rows of the same kinds) or from the rows' guesses.
  void warmStart(const ConstraintRows& rows);
  /// Projected Gauss–Seidel sweeps from the current λ, stopping on the Alart–Curnier residual.
  template <class Delassus>
  void projectedGaussSeidel(const ConstraintRows& rows, Delassus& w, int max_sweeps);
  /// max_r |F_r|/ρ_r of the current λ through the operator's products.
  template <class Delassus>
  double contactResidual(const ConstraintRows& rows, Delassus& w);
  /// R of the contact rows (setCompliance).
  void setCompliance(const ConstraintRows& rows);
  ContactNewton newton_;
  VecX wl_, compliance_, effective_diagonal_, unpolished_;  // (W + R)λ − β (residual checks), R, W_rr + R_r
  /// Contact sweeps through an operator that mixes the axes: the factored form costs less per
  /// sweep than the assembled W (row cost: points of its bodies against rows it couples to).
  bool factoredFormIsCheaper(const ConstraintProblem& problem, const ConstraintRows& rows);
  std::vector<long> rows_on_body_;
  /// W_rk through an operator that mixes the axes (columns per row, current_).
  double generalEntry(const ConstraintProblem& problem, const ConstraintRows& rows, int r, int k) const;

  Options options_;
  Statistics stats_;
  std::vector<Column> current_, previous_;
  std::vector<std::pair<std::uint64_t, int>> previous_index_;  // (hash, index in previous_)
  const BlockInverse* cached_inverse_ = nullptr;
  long cached_revision_ = -1;
  long cached_size_ = -1;
  // The contact Newton's Settings::matrix_key: the same number while the calls of one step solve
  // with the same operator (its revision) and rows, so that the last call's factorization may
  // serve chord steps (contact_newton.hpp). step_began_: no call yet in this step (or since a
  // restore); last_call_newton_: the last call solved its contacts by Newton.
  long newton_key_ = 0;
  bool step_began_ = true;
  bool last_call_newton_ = false;
  // What a deferred call left that the next call on the same W (same_w: the step's error estimate
  // after the step) would compute again, bit for bit, from the same A and rows: W's diagonal from
  // A⁻¹'s band (band_diagonal_held_, with that call's far_rows and inverse_range for the stats)
  // and W_BB of the equality rows (from A⁻¹'s band or band products), factored
  // (equality_block_key_: the newton_key_ of the deferred call that left it, −1 for none).
  bool band_diagonal_held_ = false;
  long equality_block_key_ = -1;
  int held_far_rows_ = 0, held_inverse_range_ = 0;
  // Structure of the last assembled W: factors (anchor, direction) per row and the mode.
  std::vector<int> last_factor_start_, last_factor_anchor_;
  std::vector<Vec3> last_factor_direction_;
  bool last_sparse_ = false, have_factorization_ = false;
  bool factored_last_call_ = false;  // the last call factored W (no contact rows)
  // Projected Gauss–Seidel: W's full rows, the equality rows and their block's factor.
  std::vector<int> adjacency_start_, adjacency_column_;
  std::vector<double> adjacency_value_;
  std::vector<int> equality_rows_;
  std::vector<ConstraintRows::Kind> last_kinds_;
  MatX w_bb_;
  std::vector<char> block_column_;  // W_BB's columns taken by band products (BandProductDelassus::equalityBlock)
  Eigen::LDLT<MatX> ldlt_bb_;
  VecX residual_bb_, delta_bb_;
  // Rows of the last call through an operator that mixes the axes (an implicit step matrix):
  // while the operator's revision and these rows are unchanged, its columns A⁻¹Lᵀ and W are kept.
  std::vector<int> last_row_start_, last_row_point_;
  std::vector<Vec3> last_row_coeff_;
  bool have_general_ = false;
  /// The rows are those of the last call (same points and coefficients, row by row).
  bool sameRowsAsLastCall(const ConstraintRows& rows) const;
  void rememberRows(const ConstraintRows& rows);
  long last_nonzeros_ = 0;

  MatX g_;  // G_ab = w_aᵀ M⁻¹ w_b for anchors a, b (mass operator)
  MatX w_;  // W (dense path: the lower triangle, mirrored into the upper one for contact sweeps)
  bool w_unformed_ = false;  // a deferred call left W unformed: w_ does not hold its rows' W
  DelassusSource source_ = DelassusSource::kColumns;  // of this call's W
  bool columns_ready_ = false;  // current_ holds this call's columns A⁻¹ l_r
  std::vector<std::vector<Eigen::Matrix3d>> inverse_band_;  // per body: A⁻¹ within inverse_range_ (kInverseBand)
  std::vector<BandBlocks> inverse_band_layout_;  // per body: its band's range and point groups
  std::vector<int> problem_offset_;  // per body: its first point (kInverseBand)
  /// The widest range of A⁻¹'s blocks inverseBandCovers takes on a body, in groups.
  static constexpr int kWidestInverseRange = 16;
  std::vector<int> inverse_range_;   // per body: the range of inverse_band_ (>= the band's; kInverseBand)
  std::vector<int> span_rows_;       // per body and span <= kWidestInverseRange: its rows that wide (inverseBandCovers)
  std::vector<int> far_row_;         // per row: its place in far_diagonal_, −1 within the bands (kInverseBand)
  std::vector<double> far_diagonal_;  // the far rows' W_rr (computeInverseBands)
  std::vector<int> far_point_mark_;   // per point: the row that last counted it (inverseBandCovers' distinct points)
  VecX far_work_;                     // a body's block for a far row's solve (grows only)
  VecX unit_;  // e_j (BandProductDelassus::equalityBlock; grows only)
  BandDelassusProduct band_product_;  // W x through A's band (the contact Newton's and the deferred polish's)
  AugmentedNewtonSystem equality_system_;  // solveEqualitiesThroughBand's
  std::vector<int> band_rows_;             // 0 … c − 1: every row solved, in its own place (solveEqualitiesThroughBand)
  std::vector<NewtonRowForm> equality_forms_;  // J_r = W_r
  std::vector<int> band_position_;         // row → its place in the rows solved by equality_system_, or −1
  bool equality_by_band_ = false;          // this solve's W_BB⁻¹ through equality_system_ (not ldlt_bb_)
  bool equality_pivot_refused_ = false;    // the last buildEqualitySystem met a pivot <= 0
  std::vector<char> equality_bodies_;      // per body: whether the rows equality_system_ solves act on it
  VecX band_wl_;  // W λ by band_product_ (BandProductDelassus; grows only)
  VecX saved_diagonal_;  // diagonal_ across a deferred formDelassus (grows only)
  MatX yt_;  // Yᵀ: the columns y_k = A⁻¹ l_k as rows (assembleGeneralByColumns; grows only)
  std::vector<const double*> y_start_;  // where each column's entries on a body start (the same)
  VecX diagonal_;
  std::vector<int> bucket_, bucket_start_, cursor_;  // columns to solve, grouped by body
  MatX batch_;  // right-hand sides solved together (prepareColumns: 3 n_b × kColumnBatch, grows only)
  PointInverseBlocks point_blocks_;  // A⁻¹ between touched points, kept while A is
  // assembleFromPointBlocks (all grow only): the rows' points as held slots in a compact order,
  // each term's compact coordinate, H between them (3m × 3m) and Z = H_m L_mᵀ (3m × c).
  std::vector<int> compact_of_slot_, compact_slots_, term_index_;
  MatX h_m_, z_;
  std::vector<char> body_touched_;
  // The body of each scene point, rebuilt when the scene's layout changes (refine, cut): the
  // O(c²) loops look a term's body up here instead of scanning the bodies (ConstraintProblem::bodies).
  std::vector<int> point_body_;
  long point_body_revision_ = -1;
  const ConstraintProblem* point_body_problem_ = nullptr;
  /// Brings point_body_ up to date with the problem's layout.
  void mapPointsToBodies(const ConstraintProblem& problem);
  int c_ = 0;                 // rows of the current (last) call
  VecX u_;  // A⁻¹ Lᵀ λ (FactoredDelassus)
  std::vector<std::pair<int, int>> body_span_;  // FactoredDelassus: (3 · offset, 3 · points) per body
  VecX rhs_, lambda_, force_, block_;  // rhs_, lambda_, diagonal_: capacity >= c_, used head(c_)
  Eigen::LDLT<MatX> ldlt_;
  MatX w_factored_;  // W of the current dense factorization
  std::unique_ptr<SparseFactor> sparse_;
};

}  // namespace filum::constraints
