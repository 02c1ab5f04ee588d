// ConstraintSolver: turns the unconstrained (tendency) accelerations A_t = M⁻¹B into
// accelerations that satisfy L A = E (paper §4; [Lenoir talk 2008] "acceleration decomposition") — and,
// for the inequality rows of contacts (ConstraintRows::Kind), Signorini's and Coulomb's laws.
// One solver serves every integrator: explicit stages pass the mass matrix as A, implicit steps
// their step matrix.
#pragma once

#include "filum/core/block_inverse.hpp"
#include "filum/core/component.hpp"
#include "filum/core/constraint_problem.hpp"
#include "filum/core/constraint_rows.hpp"
#include "filum/core/scene_state.hpp"

namespace filum {

class Scene;

/// What a solver's contact solves did (reports: the timing summary, bench_realtime; not physics).
/// A solve counts when its rows hold contacts (inequality rows).
struct ContactSolveTally {
  long solves = 0;
  long converged = 0;        // the residual reached the threshold
  long fell_back = 0;        // the main method gave up and a fallback finished the solve
  long iterations = 0;       // of the main method, summed
  long chord_steps = 0;      // of those iterations, steps on an earlier factorization (contact Newton's chords)
  double worst_ratio = 0.0;  // largest residual / threshold

  void add(bool solve_converged, bool solve_fell_back, int solve_iterations, double ratio, int solve_chord_steps = 0) {
    ++solves;
    converged += solve_converged ? 1 : 0;
    fell_back += solve_fell_back ? 1 : 0;
    iterations += solve_iterations;
    chord_steps += solve_chord_steps;
    if (ratio > worst_ratio || !(ratio == ratio)) worst_ratio = ratio;  // a NaN ratio stays visible
  }
};

class ConstraintSolver : public Component {
 public:
  /// Solves  A a = b,  L a = E  for a, given a_t = A⁻¹ b in `a` on entry (the constrained
  /// result on exit). `inverse` applies A⁻¹ body by body (the mass matrix for explicit steps).
  /// `problem` says where the bodies' points lie (Scene::constraintProblem()); the solver sees
  /// nothing else of the scene.
  virtual void solve(const ConstraintProblem& problem, const ConstraintRows& rows, const BlockInverse& inverse, VecX& a) = 0;
  /// λ of the last solve, one per row (N for a point row; contact rows report their force).
  virtual Eigen::Ref<const VecX> multipliers() const = 0;
  /// Writes its warm start for the next call into `memory` (Scene::endStep), and takes it back
  /// (Scene::setState): see StepMemory.
  virtual void saveMemory(StepMemory& /*memory*/) const {}
  virtual void restoreMemory(const StepMemory& /*memory*/) {}
  /// A step begins (Scene::beginStep): what a solver keeps between the solves of one step and
  /// not in StepMemory (a factorization) is dropped here, so that a step depends on the state and
  /// its StepMemory alone and a restored run repeats bit for bit.
  virtual void beginStep() {}
  /// Contact solves since construction or the last resetContactTally().
  const ContactSolveTally& contactTally() const { return tally_; }
  void resetContactTally() { tally_ = ContactSolveTally(); }

 protected:
  ContactSolveTally tally_;
};

}  // namespace filum
