// ImplicitStepSolver: the linearly implicit step (default) or Newton's method, on the analytic
// force Jacobian, for the acceleration a of a one-step implicit scheme (the implicit integration
// of paper §3, after [HMC01]):
//   M a = Q(q0 + θh v0 + κh² a,  v0 + θh a,  t0 + θh) + Lᵀλ,   L a = E(q0, v0, t0),
// with (θ, κ) = (1, 1) for backward Euler (v1 = v0 + h a, q1 = q0 + h v1) and (½, ¼) for the
// implicit midpoint rule (v1 = v0 + h a, q1 = q0 + h (v0 + v1)/2). Newton iteration k, from a_0 = 0:
//   A_k = M − θh D_k − κh² K_k                 (K = ∂Q/∂q, D = ∂Q/∂q̇ at the iterate; StepMatrix)
//   a_t = a_k + A_k⁻¹ (Q_k − M a_k)             (unconstrained Newton update)
//   a_{k+1} = a_t + A_k⁻¹ Lᵀ λ,  L a_{k+1} = E  (paper §4's decomposition with A_k in place of M)
// At convergence M a = Q + Lᵀλ holds exactly whatever A_k is (the residual is exact), so the
// symmetrised or truncated Jacobians of StepMatrix/RayleighDamping cost iterations, not accuracy.
// Converged when |a_{k+1} − a_k|∞ <= tolerance · max(|a_{k+1}|∞, |g|), or when the update stops
// shrinking (|Δa_k| > ½ |Δa_{k−1}|) at the round-off floor of the residual: below √tolerance of
// that scale, or moving the positions by θh²|Δa| <= tolerance · ℓ (ℓ the scene's extent). A
// stiff residual's floor, ε |q| |M⁻¹K| ≈ ε ℓ ω_max² for small steps, is ~1e-4 m/s² for a real
// suture: far above 1e-10 |a| when accelerations are small.
//
// The linearized solve (default, "solve": "linearized"): the first Newton iteration above is the
// linearly implicit scheme of Baraff & Witkin — one assembly, one factorization, one solve. Its
// error against the fully implicit step is estimated by one chord iteration on the same factor:
//   Δa = A⁻¹ (Q(a_1) − M a_1) projected on the constraints   (one force evaluation and one solve),
// and the step is accepted when the position error of a_1 is small against the step's own motion:
//   κh² |Δa|∞ <= linearization_tolerance · max(|θh v0 + κh² a_1|∞, newton_tolerance · ℓ)
// (the second term: the round-off floor of positions, as in Newton's test). The accepted
// acceleration is then a_2 = a_1 + Δa, the chord iterate the estimate has just computed, closer
// still to the implicit step (a chord iteration contracts the error) at no extra cost; with a
// reused matrix (below) that keeps its chord error off the trajectory: accepting a_1 lost 80 %
// more energy on the benchmark rope over 2 s and grew the cantilever's error by 5 %. Otherwise A is
// assembled at a_1, where the residual is already known, and Newton iterations go on from a_1 to
// the Newton tolerance as in "newton" mode — halving the step if they do not converge. The
// default tolerance, 1e-3, lets the linearization move a step's end by 0.1 % of the step's motion.
// A measure relative to the accelerations is not safe: with |Δa| <= 1e-2 |a_1| the catenary
// released far from equilibrium at 5 and 20 ms steps (tests/mechanics/catenary_validation_test,
// implicit_integrators_test) buckled differently and settled elsewhere (the snapping thread's
// |a| is huge); with the position measure its rest states match full Newton's to the digit.
// estimates(), corrections() and halvings() count how often each happens.
//
// Reusing the factorization ("reuse_factorization", linearized mode; default true for backward
// Euler, false for the midpoint rule, NewtonSettings::secondOrder): the first iteration of a step
// solves with the matrix factored in an earlier step (same h, θ, κ) instead of assembling a new
// one — a chord step from a Jacobian a few steps old, as stiff ODE solvers keep their Jacobian
// over many steps (Hairer & Wanner, Solving ODEs II, §IV.8). The same estimate guards it: when
// the stale estimate fails and no contact acts (inContact), one more chord iteration is taken on
// the same stale factor from
// a_2 = a_1 + Δa (one force evaluation and one solve):
//   Δa_2 = A_old⁻¹ (Q(a_2) − M a_2) projected on the constraints,
// and a_3 = a_2 + Δa_2 is accepted when κh² |Δa_2|∞ passes the same test as the estimate (the
// update just taken measures the iterate's error, as after a correction below); the next step
// then assembles afresh, so that the matrix does not age further. On the benchmark rope a stale
// estimate fails marginally (median 1.15 times the tolerance) and the second chord iteration
// passes in 199 of 209 cases: a failed reuse costs ~11 µs instead of a refresh's ~64, and the
// rope's strain and energy drift are unchanged to three digits (0.0323–0.0326 → 0.0293–0.0297 ms
// per simulated ms with the solve of BlockBandLdlt, median of 5 over 2 s, see
// apps/bench/bench_realtime --step-kinds). secondChords() counts these steps. When the
// second iteration fails too, the step is taken again from its start with a matrix assembled
// there (then exactly as without reuse: estimate, and Newton when that fails), which also
// refreshes the matrix for the next steps. Newton is not continued from the stale step's a_1:
// that iterate can be far off, and Newton from it failed often enough to halve
// hanging_thread.json's steps 755 times in 2 s (none from a fresh start). reuses() counts the
// steps that reused a matrix, refreshes() those taken again (from the force at a_0 the stale
// attempt evaluated). The next step reuses the fresh matrix; when that fails too, the next 1, 3,
// 7 … 31 steps (doubling with each failure in a row) do not reuse: in scenes where most reuses
// fail (a thread snapping taut, sliding points) reuse would cost more than it saves.
// Accuracy: a reused step passes the same estimate, but its error sits near the tolerance where a
// fresh linearized step's is far below it. On the benchmark rope (apps/scenes/rope.json, 165
// points, 1 s) the control points end within 1e-8 m of Newton's backward Euler without reuse
// and within 3e-4 m with it, while backward Euler itself is 2e-3 to 3e-2 m off the reference
// (implicit midpoint solved by Newton at 0.1 ms): reuse adds at most a few percent to the
// scheme's own error. Scenes that need more set "reuse_factorization": false.
// max_iterations = 1 skips the estimate: Baraff & Witkin's step, always accepted, and never
// reuses a matrix (nothing would guard it).
//
// Robustness. Far from equilibrium with a large step the Newton iteration may not converge: a
// compressed thread has negative stiffness directions, so M − κh²K may be indefinite and the
// Newton step overshoots. A non-converged iterate is never accepted (it can carry enormous
// energy): step() then halves h and takes two steps, recursively, towards sub-steps where M/h²
// dominates −K again: down to h/2^max_halvings (10 by default), and at most max_step_solves
// Newton solves for one step (2047 by default: every attempt of ten levels of halving). A scene
// may allow deeper sub-steps: a stiff string started away from equilibrium (a strain transient
// of microseconds: catenary.json's first steps need sub-steps of 15 µs) needs a few very short
// sub-steps and then climbs back to long ones (after a converged half, its sibling is tried
// whole), and the budget still bounds the step's work. The default depth stays 10: deeper, a
// step that cannot be taken at all is refused later — organ.json at dt × 100 took more than
// 200 s to refuse its first step at a depth of 30, 31 s at 10 (each attempt there is costly).
// Only if the halves fail too is the step reported to the scene (Scene::noteFault), which rolls
// it back. "Newton solves" are attempts (solve() calls, up to max_iterations
// iterations each; solves() counts them with the fresh retries of stale matrices); the budget is
// per call of step(), so per contact sub-step of the scene. A fault a component notes during an
// attempt (a non-finite force, or a constraint solve through a step matrix that is not definite)
// is the attempt's: taken back (Scene::takeFault) when the attempt is taken again in halves — or,
// on a reused matrix, from a fresh one — and reported with the step's failure. The iteration is also abandoned early when the update stops shrinking
// above √tolerance (from the third iteration).
//
// Bodies with internal DOFs (a rod's frames): their rotations are unknowns of the same system,
// moved by q0 ⊕ w (R exp(w)) for the increment w = θh v0 + κh² a, with their rotary inertia in
// M and their torques' Jacobians in K (MechanicalState::addInternalMassMatrix, StepMatrix's
// groups); the convergence measures count a frame's angular acceleration times its body's
// radius. The gyroscopic torque's Jacobian is left out of D (tiny for rods: ω J ω), which costs
// iterations, not accuracy (the residual is exact).
//
// Constraint rows are those of the (sub-)step's start state (Baumgarte terms included), as for
// the explicit integrators. Workspaces are allocated on the first step and reused.
#pragma once

#include <string>

#include "filum/core/params.hpp"
#include "filum/core/scene_state.hpp"
#include "filum/mechanics/step_matrix.hpp"

namespace filum {
class Scene;
}

namespace filum::mechanics {

struct NewtonSettings {
  bool linearized = true;                // "solve": "linearized" (default) or "newton"
  double linearization_tolerance = 1e-3;  // relative, see above
  bool reuse_factorization = true;        // "reuse_factorization" (linearized mode, with the estimate), see above
  int max_iterations = 10;
  double tolerance = 1e-10;
  int max_halvings = 10;       // depth: sub-steps down to h / 2^10
  int max_step_solves = 2047;  // work: Newton solves (attempts) for one step, see above
  bool refactor_every_iteration = true;
  LinearSolverChoice linear_solver = LinearSolverChoice::Auto;

  /// "solve": "linearized" (default: one Newton step and an error estimate, see above; with
  /// "linearization_tolerance", default 1e-3, and "reuse_factorization", default from the
  /// integrator) or "newton" (iterate to "newton_tolerance"),
  /// "newton_iterations": max iterations >= 1 (default 10; 1 in linearized mode is Baraff &
  /// Witkin's step without the estimate), "newton_tolerance": relative
  /// tolerance >= 0 (default 1e-10; 0 runs every iteration and accepts the last),
  /// "max_halvings": how deep a step may be halved when Newton does not converge (default 10, at
  /// most 60),
  /// "max_step_solves": Newton solves allowed for one step, the halves' included (default 2047),
  /// "jacobian_update": "every_iteration" (Newton, default) or "every_step" (the chord method:
  /// A factored once per step from the start of the iteration, later iterations only evaluate
  /// forces and solve; linear convergence, cheaper iterations — worth it when h is small and A
  /// changes little within a step), "linear_solver".
  /// `defaults` supplies what the scene leaves out (the integrator's own defaults).
  static NewtonSettings fromParams(const Params& p, const NewtonSettings& defaults);
  static NewtonSettings fromParams(const Params& p) { return fromParams(p, NewtonSettings()); }
  /// The midpoint rule's defaults: no factorization reuse (see ImplicitMidpoint).
  static NewtonSettings secondOrder() {
    NewtonSettings settings;
    settings.reuse_factorization = false;
    return settings;
  }
};

class ImplicitStepSolver {
 public:
  explicit ImplicitStepSolver(NewtonSettings settings)
      : settings_(settings), matrix_(settings.linear_solver) {}

  enum class Status { kConverged, kNotConverged, kFailed };

  /// Newton for a (3N, m/s²) at step size h from state s0. kFailed: the step matrix could not
  /// be factored or a is not finite (lastFailure() says which).
  Status solve(Scene& scene, const SceneState& s0, double h, double theta, double kappa, VecX& a);

  /// Advances s over h with the scheme (θ, κ): v1 = v0 + h a, q1 = q0 + h v0 + c h² a
  /// (c = position_factor: 1 for backward Euler, ½ for the midpoint rule), halving h when
  /// Newton does not converge (see above). False after Scene::noteFault when it cannot.
  bool step(Scene& scene, SceneState& s, double h, double theta, double kappa, double position_factor);

  const NewtonSettings& settings() const { return settings_; }
  int lastIterations() const { return last_iterations_; }
  long totalIterations() const { return total_iterations_; }
  /// Newton solves (one per step, more when steps were halved).
  long solves() const { return solves_; }
  /// Steps that had to be halved.
  long halvings() const { return halvings_; }
  /// Linearized solves whose error was estimated, and those the estimate sent on to Newton.
  long estimates() const { return estimates_; }
  long corrections() const { return corrections_; }
  /// Steps whose first iteration reused an earlier factorization, and those of them whose
  /// estimate failed, so that the step was taken again from a fresh matrix.
  long reuses() const { return reuses_; }
  long refreshes() const { return refreshes_; }
  /// Reuses whose estimate failed and that took a second chord iteration on the stale matrix
  /// (refreshes() counts those that failed that too).
  long secondChords() const { return second_chords_; }
  const std::string& lastFailure() const { return failure_; }
  const StepMatrix& matrix() const { return matrix_; }

  /// The kept factorization (its id, key and linearization point) and the reuse schedule into
  /// `memory`; restoreMemory puts them back, assembling the kept matrix again at its point when it
  /// is not the one held — the same bits where assembly is a function of that state alone. Not
  /// for a penalty contact response (its stiffness is that of the contact set detected when the
  /// matrix was assembled, which the memory does not keep) nor RayleighDamping "per_step" (its
  /// K lags to the step's first evaluation): there the rerun differs within the linearization's
  /// tolerance (2.9e-7 m measured on paper_threads.json under ImplicitEuler).
  void saveMemory(StepMemory& memory) const;
  void restoreMemory(const Scene& scene, const StepMemory& memory);

 private:
  bool advance(Scene& scene, SceneState& s, double h, double theta, double kappa, double position_factor,
               int depth);
  int step_solves_ = 0;  // Newton solves of the current step (halves included)
  bool attempt_reused_ = false;  // the last iterate() started on an earlier step's matrix
  /// What solve() does once: with may_reuse, the first iteration may solve with an earlier
  /// factorization; kStale when it did and its estimate failed.
  enum class Attempt { kConverged, kNotConverged, kFailed, kStale };
  /// first_force_known: the force at a_0 is first_force_ (kept by the stale attempt before).
  Attempt iterate(Scene& scene, const SceneState& s0, double h, double theta, double kappa, VecX& a, bool may_reuse,
                  bool first_force_known = false);
  /// Whether the step's contact set holds a contact: a stale matrix's second chord iteration
  /// is then not taken (its contact forces come through the stale Delassus operator, which the
  /// estimate does not measure: on threads.json two loops' centre lines then came within
  /// 0.94 mm, below the one radius, 1 mm, that tests/collision/scene_files_test.cpp allows).
  static bool inContact(const Scene& scene);
  /// eval_ := the iterate's state (q0 + θh v0 + κh² a, v0 + θh a), force_ := Q − M a there
  /// (a_is_zero: a = a_0 = 0, M a not computed).
  void residualAt(Scene& scene, const SceneState& s0, double h, double theta, double kappa, const VecX& a,
                  bool a_is_zero);
  /// next_ = a + A⁻¹ r with r in force_ (overwritten), constrained; false if not finite.
  bool update(Scene& scene, const SceneState& s0, const VecX& a, int k);
  /// force_ := A⁻¹ force_ over the points and the bodies' internal DOFs.
  void solveStep(const Scene& scene);
  /// |next − a|∞ over the points (m/s²) and the internal DOFs times their body's radius.
  static double change(const Scene& scene, const VecX& next, const VecX& a);

  NewtonSettings settings_;
  StepMatrix matrix_;
  SceneState eval_;      // the state the forces are evaluated at
  VecX a_, force_, ma_, next_;
  VecX residual_;  // Q − M a at a_1, kept for the Newton iteration that may follow the estimate
  VecX first_force_;  // Q at a_0 of an attempt that reuses a matrix (the fresh attempt after it starts there)
  VecX increment_;    // θh v0 + κh² a, the step's velocity-space increment (bodies with internal DOFs)
  VecX internal_ma_;  // M a of the internal DOFs (velocity layout)
  VecX packed_;       // points and internal DOFs in the step matrix's group order
  std::string failure_;
  int last_iterations_ = 0;
  long total_iterations_ = 0;
  long solves_ = 0;
  long halvings_ = 0;
  long estimates_ = 0;
  long corrections_ = 0;
  long reuses_ = 0;
  long refreshes_ = 0;
  long second_chords_ = 0;
  bool fresh_next_ = false;  // a step passed on its second chord iteration: the next one assembles afresh
  static constexpr int kMaxReuseBackoff = 31;  // steps without reuse after failed reuses in a row
  int reuse_backoff_ = 0;                      // current backoff (0 after a reuse that passed)
  int reuse_skip_ = 0;                         // steps left that assemble afresh
  /// Assembles and factors A at eval_ for (h, θ, κ); remembers them for reuse.
  bool assembleAt(const Scene& scene, double h, double theta, double kappa);
  bool matrix_valid_ = false;        // matrix_ holds a factorization for matrix_key_
  long matrix_id_ = 0;               // unique in the process per assembly (StepMemory::matrix_id)
  double linearization_time_ = 0.0;  // the state matrix_ was assembled at (eval_ then)
  VecX linearization_q_, linearization_v_;
  double matrix_key_[3] = {0, 0, 0};  // h, θ, κ of that factorization
};

}  // namespace filum::mechanics
