// Unilateral contacts with the bilateral constraints (DESIGN.md, constraints library: "Signorini,
// Delassus operator, projected Gauss–Seidel"; talk 002, catheter: "Signorini's law 0 <= d ⊥ f >= 0
// ... Delassus operator W = H C Hᵀ"): contacts as inequality rows of the acceleration system, so
// that a knot cannot slip through itself however fast it is pulled (the paper's penalty knots
// are "unstable and breakable", §4–5).
//
// At each integrator stage, with a_t = A⁻¹ b the unconstrained accelerations and J the rows,
//   a = a_t + A⁻¹ Jᵀ λ,    W = J A⁻¹ Jᵀ (Delassus operator),   W λ − β = J a − rhs,  β = rhs − J a_t,
// for three kinds of rows:
//   bilateral rows (the scene's constraints, L a = E):          W_r λ = β_r, λ_r free;
//   contact normal rows n·(a_A − a_B) >= −2ω ġ − ω² g:          λ_n >= 0, (Wλ − β)_n >= 0,
//                                                               λ_n (Wλ − β)_n = 0 (Signorini,
//     at the acceleration level with Baumgarte's critically damped correction: a resting or
//     speculative contact (g > 0 but closing, from continuous detection) is held at g >= 0 to
//     within ġ/(ω e) — the contact engages before the chords touch when they close fast);
//   friction rows t_j·(a_A − a_B) = −ω_f t_j·(v_A − v_B), j = 1, 2: |(λ_t1, λ_t2)| <= μ λ_n
//     (Coulomb's disc, sticking drives the slip speed to zero at rate ω_f).
// Solved by projected block Gauss–Seidel: each sweep solves the bilateral block exactly
// (Δλ_B = W_BB⁻¹ (β_B − W_B·λ), W_BB factored once per stage by LDLᵀ), then every contact row
// in order, λ_r ← proj(λ_r + (β_r − W_r·λ)/W_rr), friction pairs projected on the disc. This is
// block coordinate descent on the convex problem min ½ λᵀWλ − βᵀλ over the admissible set, so
// it converges for W positive semi-definite (also when contacts are redundant: a thread lying on
// a plane has more contacts than degrees of freedom); it stops when no row's acceleration
// changes by more than tolerance · max|β| (W_rr |Δλ_r|, m/s²), or after `iterations` sweeps.
//
// W is never formed: the sweeps run on the accelerations themselves (as Bullet's and ODE's
// solvers do), keeping a = a_t + Σ_r y_r λ_r with y_r = A⁻¹ J_rᵀ, so that
//   β_r − W_r·λ = rhs_r − J_r a   (O(d) per row),   a += y_r Δλ_r   (O(n_b) per row).
// The columns y_r cost one A⁻¹ solve each on the bodies the row touches. When A is the mass
// matrix (the same n_b × n_b block on x, y and z, paper eq. 3; BlockInverse::sameOnEveryAxis)
// they are built from anchors, as in LagrangeMultiplierSolver: a contact's three rows are one
// anchor w (the weights of its points, + on A, − on B) in three directions e, so
// y = (M⁻¹ w) ⊗ e — one scalar solve serves the normal and both friction rows, and three anchors
// share one 3-column band solve (x, y, z columns). Otherwise (implicit step matrices mix the
// coordinates) every row gets its own 3-column solve. Cost per stage: O(anchors · n_b) for the
// columns, W_rr and W_BB from them, and O(c n_b) per sweep — against O(c²) for a sweep over an
// assembled W. Buffers are kept from call to call (no allocation once the largest contact set
// was seen).
#pragma once

#include <vector>

#include <Eigen/Cholesky>

#include "filum/collision/contact.hpp"
#include "filum/core/block_inverse.hpp"
#include "filum/core/constraint_rows.hpp"

namespace filum {
class Scene;
}

namespace filum::collision {

class UnilateralContactSolver {
 public:
  struct Settings {
    double stabilization = 0.0;  // ω (1/s) of the normal rows > 0
    double friction_rate = 0.0;  // ω_f (1/s) of the friction rows > 0
    int iterations = 200;        // sweeps at most
    double tolerance = 1e-6;     // relative
  };
  struct Statistics {
    int rows = 0;          // bilateral + contact rows
    int bilateral = 0;
    int sweeps = 0;
    double change = 0.0;   // last sweep's largest W_rr |Δλ_r| (m/s²)
    long solves = 0;       // since construction
    long total_sweeps = 0; // since construction
  };

  /// On entry a = A⁻¹ b; on exit the constrained accelerations. Contacts are evaluated at s.
  void solve(const Scene& scene, const SceneState& s, const ConstraintRows& bilateral, const ContactSet& contacts,
             const BlockInverse& inverse, const Settings& settings, VecX& a);

  /// Normal force λ_n (N) of every contact of the last solve, in contact order.
  const std::vector<double>& normalForces() const { return normal_force_; }
  /// Force on thread point A of every contact of the last solve (N): λ_n n + λ_t1 t1 + λ_t2 t2.
  const std::vector<Vec3>& contactForces() const { return contact_force_; }
  const Statistics& statistics() const { return stats_; }
  /// Forget the warm start (a new contact set).
  void resetWarmStart() { warm_rows_ = -1; }

 private:
  enum class RowKind : char { kBilateral, kNormal, kFriction };
  /// A⁻¹ applied to something on one body: a whole row (3 n_b values, general path) or an anchor
  /// (n_b values, one per point, factored path), stored at y_[start].
  struct Column {
    int owner;  // row (general path) or anchor (factored path)
    int body;   // −1: the whole scene vector (coupled inverse, general path)
    int start;
  };

  void buildRows(const SceneState& s, const ConstraintRows& bilateral, const ContactSet& contacts,
                 const Settings& settings);
  /// General path: y_r = A⁻¹ J_rᵀ row by row.
  void solveRowColumns(const Scene& scene, const BlockInverse& inverse);
  /// Factored path: z_a = M⁻¹ w_a anchor by anchor, three to a band solve.
  void solveAnchorColumns(const Scene& scene, const BlockInverse& inverse);
  /// W_rk = J_r · y_k.
  double delassus(const Scene& scene, int r, int k) const;
  /// a += Δλ y_r.
  void addColumn(const Scene& scene, int r, double delta, VecX& a) const;
  /// Start in y_ of the column of `owner` on body b, or −1 (−2: the whole-scene column).
  int columnStart(int owner, int b) const;
  void iterate(const Scene& scene, const Settings& settings, VecX& a);

  ConstraintRows rows_;
  bool factored_ = false;
  std::vector<RowKind> kind_;
  std::vector<int> contact_of_row_;   // contact index of contact rows, −1 for bilateral
  std::vector<int> normal_row_;       // normal row of every contact
  std::vector<Vec3> direction_;       // n, t1 or t2 of contact rows
  std::vector<double> mu_;            // μ of friction rows
  std::vector<int> term_body_;        // body of every expanded term of rows_
  std::vector<int> column_start_;     // columns of owner o: [column_start_[o], column_start_[o+1])
  std::vector<Column> columns_;
  std::vector<int> by_body_;          // factored path: columns grouped by body
  VecX y_;
  VecX work_;                         // one body's 3-column right-hand side (the largest body's size)
  std::vector<double> diagonal_;      // W_rr
  std::vector<double> coupling_;      // W_{t2,t1} of friction pairs
  std::vector<double> lambda_;        // multipliers (N)
  VecX scratch_, solved_;             // bilateral block
  MatX w_bb_;
  Eigen::LDLT<MatX> ldlt_;
  int warm_rows_ = -1;
  std::vector<double> normal_force_;
  std::vector<Vec3> contact_force_;
  Statistics stats_;
};

}  // namespace filum::collision
