#include "filum/mechanics/implicit_step_solver.hpp"

#include <atomic>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "filum/core/collision_pipeline.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene.hpp"

namespace filum::mechanics {

namespace {
/// A (sub-)step's length for a message: "4.88e-04 s" (fixed decimals would print the deepest
/// sub-steps as 0).
std::string duration(double h) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g s", h);
  return text;
}
}  // namespace

NewtonSettings NewtonSettings::fromParams(const Params& p, const NewtonSettings& defaults) {
  NewtonSettings settings = defaults;
  const std::string solve = p.string("solve", "linearized");
  if (solve != "linearized" && solve != "newton") p.fail("solve", "\"linearized\" or \"newton\"", "\"" + solve + "\"");
  settings.linearized = solve == "linearized";
  settings.max_iterations = p.integer("newton_iterations", 1, settings.max_iterations);
  settings.max_halvings = p.has("max_halvings") ? p.integer("max_halvings", 0, 60, "a sub-step of h / 2^60 is below the round-off of any time") : settings.max_halvings;
  settings.max_step_solves = p.has("max_step_solves") ? p.integer("max_step_solves", 1) : settings.max_step_solves;
  settings.tolerance = p.nonNegative({"newton_tolerance", "1"}, settings.tolerance);
  if (settings.linearized) {
    settings.linearization_tolerance = p.positive({"linearization_tolerance", "1"}, settings.linearization_tolerance);
    settings.reuse_factorization = p.boolean("reuse_factorization", settings.reuse_factorization);
  } else {
    const std::string update = p.string("jacobian_update", "every_iteration");
    if (update != "every_iteration" && update != "every_step")
      p.fail("jacobian_update", "\"every_iteration\" or \"every_step\"", "\"" + update + "\"");
    settings.refactor_every_iteration = update == "every_iteration";
  }
  settings.linear_solver = linearSolverFromParams(p);
  return settings;
}

ImplicitStepSolver::Status ImplicitStepSolver::solve(Scene& scene, const SceneState& s0, double h, double theta,
                                                     double kappa, VecX& a) {
  // Only with the estimate (max_iterations > 1) to guard it: Baraff & Witkin's step alone would
  // keep a stale matrix forever.
  // A failed reuse is taken again from a fresh matrix, which the next step reuses. When that
  // reuse fails too (failures in a row), the next 1, 3, 7, ... 31 steps assemble afresh (the
  // backoff doubles with each failure in a row, and resets with a reuse that passes): a failed
  // reuse wastes a force evaluation and two solves, a reuse that passes saves an assembly and a
  // factorization, so reuse pays only while most reuses pass. An isolated failure (a matrix that
  // has aged) costs no forced assembly: on the benchmark rope every failure was isolated, and
  // forcing one more fresh step after each cost 5 µs per step on average. A reuse that passes
  // only on its second chord iteration (a matrix at the limit of its age) makes the next step
  // assemble afresh (fresh_next_): a step cheaper than a refresh, which keeping the aged matrix
  // would soon cost.
  const bool may_reuse = settings_.linearized && settings_.reuse_factorization && settings_.max_iterations > 1 &&
                         reuse_skip_ == 0 && !fresh_next_;
  fresh_next_ = false;
  if (reuse_skip_ > 0) --reuse_skip_;
  // An attempt on a reused matrix that failed outright (a non-finite force or constraint solve at
  // its iterate) counts as a stale one: taken again from a fresh matrix, its fault taken back.
  const bool clean = scene.fault().empty();
  Attempt attempt = iterate(scene, s0, h, theta, kappa, a, may_reuse);
  const bool failed_on_reuse = attempt == Attempt::kFailed && attempt_reused_;
  if (attempt == Attempt::kStale || failed_on_reuse) {
    ++refreshes_;
    reuse_skip_ = reuse_backoff_;
    reuse_backoff_ = std::min(2 * reuse_backoff_ + 1, kMaxReuseBackoff);
    if (failed_on_reuse && clean) scene.takeFault();
    attempt = iterate(scene, s0, h, theta, kappa, a, false, /*first_force_known=*/!failed_on_reuse);
  } else if (may_reuse) {
    reuse_backoff_ = 0;
  }
  switch (attempt) {
    case Attempt::kConverged: return Status::kConverged;
    case Attempt::kFailed: return Status::kFailed;
    default: return Status::kNotConverged;
  }
}

ImplicitStepSolver::Attempt ImplicitStepSolver::iterate(Scene& scene, const SceneState& s0, double h, double theta,
                                                        double kappa, VecX& a, bool may_reuse, bool first_force_known) {
  // a holds the 3N point accelerations, then those of the constraints' extra DOFs (a sliding
  // point's s̈): these follow from the constrained point accelerations (Scene::applyConstraints,
  // stage 3d), so the Newton system and its convergence test are on the points only.
  const Eigen::Index size = scene.velocitySize();  // points, extra DOFs, internal DOFs
  const Eigen::Index n3 = 3 * scene.dofPointCount();
  a.setZero(size);  // a_0 = 0: the first iterate evaluates forces at (q0 ⊕ θh v0, v0)
  eval_.time = s0.time + theta * h;
  eval_.steps = s0.steps;
  ma_.resize(n3);
  if (scene.hasInternalDofs()) internal_ma_.setZero(size);
  const double gravity = scene.settings().gravity.norm();
  const bool fixed_count = settings_.max_iterations == 1 || (!settings_.linearized && settings_.tolerance == 0.0);
  // ℓ: the extent of the scene (largest side of the points' bounding box), the length scale of
  // the round-off test below.
  const Eigen::Index points = n3 / 3;
  const auto coordinates = Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>>(s0.q.data(), 3, points);
  const double extent = points > 0 ? (coordinates.rowwise().maxCoeff() - coordinates.rowwise().minCoeff()).maxCoeff() : 0.0;
  ++solves_;
  last_iterations_ = 0;
  double previous_change = 0.0;
  double linearized_displacement = 0.0;  // linearized mode: max(|θh v0 + κh² a_1|∞, floor)

  bool reused = false;  // the first iteration solved with an earlier step's matrix
  attempt_reused_ = false;
  for (int k = 0; k < settings_.max_iterations; ++k) {
    // Residual r = Q(q, v) − M a at the iterate. At a_0 = 0 (M a_0 = 0) after a stale attempt:
    // Q(q0 + θh v0, v0), which that attempt evaluated and kept.
    if (k == 0 && first_force_known) {
      if (scene.hasInternalDofs())
        scene.integratePositions(s0.q, s0.v, theta * h, eval_.q);
      else
        eval_.q = s0.q + (theta * h) * s0.v;
      eval_.v = s0.v;
      force_ = first_force_;
    } else {
      residualAt(scene, s0, h, theta, kappa, a, /*a_is_zero=*/k == 0);
    }

    // A = M − θh D − κh² K at the iterate, factored: at every Newton iterate, at the first only
    // for the chord method; in linearized mode not for the estimate (k = 1, which assembles at a_1 itself when it fails) nor for the
    // check after a correction (k = 2, a chord step on the matrix of a_1).
    bool refactor = settings_.linearized ? (k == 0 || k >= 3) : (k == 0 || settings_.refactor_every_iteration);
    if (k == 0 && may_reuse && matrix_valid_ && matrix_key_[0] == h &&
        matrix_key_[1] == theta && matrix_key_[2] == kappa && matrix_.laidOutFor(scene)) {
      refactor = false;  // a chord step on an earlier factorization; the estimate guards it
      reused = true;
      attempt_reused_ = true;
      ++reuses_;
      first_force_ = force_;  // for the fresh attempt, should this one be stale
    }
    if (refactor && !assembleAt(scene, h, theta, kappa)) return Attempt::kFailed;

    // a_t = a + A⁻¹ r, then the constraints through A⁻¹.
    const bool estimate = settings_.linearized && k == 1;
    if (estimate) residual_ = force_;
    if (!update(scene, s0, a, k)) return Attempt::kFailed;
    double change = this->change(scene, next_, a);
    if (estimate) {
      // The error estimate of the linearized step a_1 (one chord iteration): a_1 is accepted as
      // it is when small enough; else this iteration becomes a Newton one from a_1, with A
      // assembled at a_1 and the residual already evaluated there.
      ++estimates_;
      const double displacement = (eval_.q - s0.q).head(n3).lpNorm<Eigen::Infinity>();  // θh v0 + κh² a_1
      const double floor = settings_.tolerance * extent;  // round-off level of positions (see Newton's test)
      linearized_displacement = std::max(displacement, floor);
      if (kappa * h * h * change <= settings_.linearization_tolerance * linearized_displacement) {
        a.swap(next_);  // a_2 = a_1 + Δa: the chord iterate the estimate computed, closer still
        return Attempt::kConverged;
      }
      if (reused && !inContact(scene)) {
        // A stale matrix's estimate failed: one more chord iteration on it, from a_2 = a_1 + Δa
        // (one force evaluation and one solve), under the same test; a_3 is accepted when it
        // passes, and the next step assembles afresh (see the header). Else the step is taken
        // again from a fresh matrix.
        ++second_chords_;
        a.swap(next_);  // a_2
        residualAt(scene, s0, h, theta, kappa, a, false);
        if (!update(scene, s0, a, k)) return Attempt::kFailed;
        change = this->change(scene, next_, a);
        if (kappa * h * h * change > settings_.linearization_tolerance * linearized_displacement) return Attempt::kStale;
        a.swap(next_);  // a_3 = a_2 + Δa_2
        fresh_next_ = true;
        return Attempt::kConverged;
      }
      if (reused) return Attempt::kStale;  // in contact: taken again from a fresh matrix
      ++corrections_;
      if (!assembleAt(scene, h, theta, kappa)) return Attempt::kFailed;
      force_ = residual_;
      if (!update(scene, s0, a, k)) return Attempt::kFailed;
      change = this->change(scene, next_, a);
    }
    a.swap(next_);
    ++last_iterations_;
    ++total_iterations_;
    if (fixed_count) continue;
    // Linearized mode after a correction: the update just taken, from the corrected iterate,
    // measures that iterate's error the way the estimate measured a_1's; when it passes the same
    // test, the updated iterate (more accurate still) is accepted.
    // The scale is a_1's displacement, not the iterate's own: an iterate that overshot far would
    // pass a test relative to its own motion.
    if (settings_.linearized && k >= 2 &&
        kappa * h * h * change <= settings_.linearization_tolerance * linearized_displacement)
      return Attempt::kConverged;
    // Newton's convergence test (in linearized mode after a failed estimate: the estimate was a
    // chord iteration, and Newton goes on to the full tolerance, as in "newton" mode).
    const double scale = std::max(a.head(n3).lpNorm<Eigen::Infinity>(), gravity);
    if (change <= settings_.tolerance * scale) return Attempt::kConverged;
    // Newton contracts quadratically; the chord method linearly, at a rate below 1.
    const double contraction = settings_.refactor_every_iteration ? 0.5 : 1.0;
    if (k >= 1 && change > contraction * previous_change) {
      // No longer contracting: either the round-off floor of the residual is reached — the
      // update is below √tolerance of the acceleration scale, or it moves the positions by less
      // than tolerance · ℓ (θh² |Δa|: the floor of a stiff residual, ε |q| |M⁻¹K|, can exceed
      // tiny accelerations) — accept; or Newton is not converging: give up from the third
      // iteration on (the caller halves the step).
      if (change <= std::sqrt(settings_.tolerance) * scale || theta * h * h * change <= settings_.tolerance * extent)
        return Attempt::kConverged;
      if (k >= 2) return Attempt::kNotConverged;
    }
    previous_change = change;
  }
  return fixed_count ? Attempt::kConverged : Attempt::kNotConverged;
}

bool ImplicitStepSolver::assembleAt(const Scene& scene, double h, double theta, double kappa) {
  static std::atomic<long> next_id{0};
  failure_ = matrix_.assemble(scene, eval_, -kappa * h * h, -theta * h);
  matrix_valid_ = failure_.empty();
  matrix_key_[0] = h;
  matrix_key_[1] = theta;
  matrix_key_[2] = kappa;
  // Where it was assembled, for StepMemory (copies into storage of the layout's size: no
  // allocation in a steady step).
  matrix_id_ = matrix_valid_ ? ++next_id : 0;
  linearization_time_ = eval_.time;
  linearization_q_ = eval_.q;
  linearization_v_ = eval_.v;
  return matrix_valid_;
}

void ImplicitStepSolver::saveMemory(StepMemory& memory) const {
  memory.reuse_skip = reuse_skip_;
  memory.reuse_backoff = reuse_backoff_;
  memory.fresh_next = fresh_next_;
  const long id = matrix_valid_ ? matrix_id_ : 0;
  if (memory.matrix_id == id) return;  // the same matrix as at the last save: nothing to copy
  memory.matrix_id = id;
  memory.matrix_key[0] = matrix_key_[0];
  memory.matrix_key[1] = matrix_key_[1];
  memory.matrix_key[2] = matrix_key_[2];
  memory.matrix_time = linearization_time_;
  memory.matrix_q = linearization_q_;
  memory.matrix_v = linearization_v_;
}

void ImplicitStepSolver::restoreMemory(const Scene& scene, const StepMemory& memory) {
  reuse_skip_ = memory.reuse_skip;
  reuse_backoff_ = memory.reuse_backoff;
  fresh_next_ = memory.fresh_next;
  if (memory.matrix_id == 0) {
    matrix_valid_ = false;
    return;
  }
  if (matrix_valid_ && matrix_id_ == memory.matrix_id && matrix_.laidOutFor(scene)) return;  // held already
  eval_.time = memory.matrix_time;
  eval_.q = memory.matrix_q;
  eval_.v = memory.matrix_v;
  if (assembleAt(scene, memory.matrix_key[0], memory.matrix_key[1], memory.matrix_key[2]))
    matrix_id_ = memory.matrix_id;  // the same matrix, bit for bit
}

bool ImplicitStepSolver::inContact(const Scene& scene) {
  const CollisionPipeline* collision = scene.collisionPipeline();
  return collision && collision->contactCount() > 0;
}

void ImplicitStepSolver::residualAt(Scene& scene, const SceneState& s0, double h, double theta, double kappa,
                                    const VecX& a, bool a_is_zero) {
  // The iterate's state: q = q0 ⊕ (θh v0 + κh² a) (q0 + ... for points; R exp(...) for frames),
  // v = v0 + θh a; r = Q(q, v) − M a.
  const Eigen::Index n3 = 3 * scene.dofPointCount();
  if (scene.hasInternalDofs()) {
    increment_ = (theta * h) * s0.v + (kappa * h * h) * a;
    scene.integratePositions(s0.q, increment_, 1.0, eval_.q);
  } else {
    eval_.q = s0.q + (theta * h) * s0.v + (kappa * h * h) * a;
  }
  eval_.v = s0.v + (theta * h) * a;
  scene.computeForce(eval_, force_);
  if (a_is_zero) return;  // M a_0 = 0
  for (const MechanicalState* body : scene.bodies()) {
    body->multiplyMass(body->block(a), body->block(ma_));
    if (body->internalVelocityCount() > 0) {
      auto internal = body->internalVelocities(internal_ma_);
      body->multiplyInternalMass(body->internalVelocities(a), internal);
      body->internalVelocities(force_) -= internal;
    }
  }
  force_.head(n3) -= ma_.head(n3);
}

double ImplicitStepSolver::change(const Scene& scene, const VecX& next, const VecX& a) {
  // Points in m/s²; a frame's angular acceleration times the body's radius (how fast its
  // surface moves by it), so that a rod's frames converge with its points.
  const Eigen::Index n3 = 3 * scene.dofPointCount();
  double largest = (next - a).head(n3).lpNorm<Eigen::Infinity>();
  if (!scene.hasInternalDofs()) return largest;
  for (const MechanicalState* body : scene.bodies()) {
    const CurveBody* curve = body->curve();
    if (body->internalVelocityCount() == 0 || !curve) continue;
    const int first = body->internalVelocityOffset(), count = body->internalVelocityCount();
    largest = std::max(largest, curve->radius() * (next.segment(first, count) - a.segment(first, count)).lpNorm<Eigen::Infinity>());
  }
  return largest;
}

void ImplicitStepSolver::solveStep(const Scene& scene) {
  // force_ := A⁻¹ force_ on the points and the internal DOFs (the extra DOFs carry no force).
  const Eigen::Index n3 = 3 * scene.dofPointCount();
  if (!scene.hasInternalDofs()) {
    matrix_.solveAll(force_.head(n3));
    return;
  }
  // Group order for the step matrix: points, then the internal triples (after the extra DOFs in v).
  const Eigen::Index internal = scene.velocitySize() - (n3 + scene.extraDofCount());
  packed_.resize(n3 + internal);
  packed_.head(n3) = force_.head(n3);
  packed_.tail(internal) = force_.tail(internal);
  matrix_.solveAll(packed_);
  force_.head(n3) = packed_.head(n3);
  force_.tail(internal) = packed_.tail(internal);
}

bool ImplicitStepSolver::update(Scene& scene, const SceneState& s0, const VecX& a, int k) {
  // next = a + A⁻¹ r (r in force_, solved in place), then constrained through A⁻¹ (which also
  // sets the extra DOFs' accelerations after the points).
  // The forces are laid out as v (scene_state.hpp): the points' 3N, then the extra DOFs (no force).
  const Eigen::Index n3 = 3 * scene.dofPointCount();
  solveStep(scene);
  next_.resize(a.size());
  next_.head(n3) = a.head(n3) + force_.head(n3);
  next_.segment(n3, scene.extraDofCount()).setZero();
  const Eigen::Index internal = a.size() - n3 - scene.extraDofCount();
  next_.tail(internal) = a.tail(internal) + force_.tail(internal);
  scene.applyConstraints(s0, matrix_, next_);
  if (next_.allFinite()) return true;
  failure_ = "Newton iteration " + std::to_string(k + 1) + " produced non-finite accelerations";
  return false;
}

bool ImplicitStepSolver::step(Scene& scene, SceneState& s, double h, double theta, double kappa,
                              double position_factor) {
  step_solves_ = 0;
  if (advance(scene, s, h, theta, kappa, position_factor, 0)) return true;
  scene.noteFault(scene.integrator().describe() + ": " + failure_);
  return false;
}

bool ImplicitStepSolver::advance(Scene& scene, SceneState& s, double h, double theta, double kappa,
                                 double position_factor, int depth) {
  if (step_solves_ >= settings_.max_step_solves) {  // the halves before this one spent the budget
    failure_ = "the step's Newton solves (max_step_solves " + std::to_string(settings_.max_step_solves) +
               ") ran out before its sub-steps of " + duration(h) + " were taken";
    return false;
  }
  ++step_solves_;
  // A fault a component records during the attempt (a non-finite force or constraint solve at a
  // wild iterate: its accelerations are then not finite, and the attempt fails) belongs to the
  // attempt: it is taken back when the attempt is discarded for its halves, and reported with the
  // step's failure if the halves fail too. (An attempt that converged would keep it.)
  const bool clean = scene.fault().empty();
  const Status status = solve(scene, s, h, theta, kappa, a_);
  const std::string attempt_fault = clean && !scene.fault().empty() ? scene.takeFault() : std::string();
  if (status == Status::kConverged) {
    if (!attempt_fault.empty()) scene.noteFault(attempt_fault);
    // v1 = v0 + h a,  q1 = q0 ⊕ (h v0 + c h² a) (q0 + ... for points, R exp(...) for frames).
    if (scene.hasInternalDofs()) {
      increment_ = h * s.v + (position_factor * h * h) * a_;
      scene.integratePositions(s.q, increment_, 1.0, s.q);
    } else {
      s.q += h * s.v + (position_factor * h * h) * a_;
    }
    s.v += h * a_;
    s.time += h;
    return true;
  }
  if (!clean) return false;  // a fault from before the step's solve (the scene rolls the step back)
  if (!attempt_fault.empty()) failure_ += " (" + attempt_fault + ")";
  // Two more solves at least: within the step's budget, and h/2 within the depth allowed.
  if (depth >= settings_.max_halvings || step_solves_ + 2 > settings_.max_step_solves) {
    if (status == Status::kNotConverged)
      failure_ = "Newton did not converge in " + std::to_string(settings_.max_iterations) +
                 " iterations, even in sub-steps of " + duration(h) + " (" + std::to_string(step_solves_) +
                 " Newton solves for this step; " +
                 (depth >= settings_.max_halvings ? "max_halvings " + std::to_string(settings_.max_halvings) + " reached)"
                                                  : "max_step_solves " + std::to_string(settings_.max_step_solves) + " reached)");
    return false;
  }
  // Two steps of h/2 (the state advances through the first before the second starts).
  ++halvings_;
  return advance(scene, s, 0.5 * h, theta, kappa, position_factor, depth + 1) &&
         advance(scene, s, 0.5 * h, theta, kappa, position_factor, depth + 1);
}

}  // namespace filum::mechanics
