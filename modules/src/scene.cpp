#include "filum/core/scene.hpp"

#include "filum/core/curve_body.hpp"

#include <algorithm>
#include <cmath>

#include "filum/core/flush_denormals.hpp"
#include "filum/core/params.hpp"
#include "filum/core/scene_error.hpp"

namespace filum {

std::string stepCountProblem(double duration, double dt) {
  const double steps = std::round(duration / dt);
  const auto number = [](double x) { return describeJson(nlohmann::json(x)); };
  if (steps < 1.0) return number(duration) + " s, shorter than dt / 2 = " + number(dt / 2) + " s (0 steps)";
  if (steps > static_cast<double>(kMaxSteps))
    return number(duration) + " s, " + number(steps) + " steps of dt = " + number(dt) + " s";
  return "";
}

Scene::Scene() : root_(std::make_unique<Node>("root")) {}

MechanicalState* Scene::bodyAt(const std::string& path) const {
  Node* node = root_->find(path);
  return node ? node->mechanicalState() : nullptr;
}

void Scene::bindBodyComponent(BodyComponent& component) {
  Node* node = component.node();
  if (!component.objectPath().empty()) {
    node = root_->find(component.objectPath());
    if (!node) {
      std::vector<std::string> paths;
      root_->listPaths(paths);
      std::string known;
      for (const auto& p : paths) known += (known.empty() ? "" : ", ") + p;
      throw SceneError(component.origin() + "/object",
                       "the path of an existing node (known nodes: " + known + ")",
                       "\"" + component.objectPath() + "\"");
    }
  }
  MechanicalState* body = node->mechanicalState();
  if (!body) {
    // Point at "object" when the scene named the node, and never print the root as "node ''".
    const std::string where = component.objectPath().empty() ? component.origin() : component.origin() + "/object";
    const std::string place = node->path().empty() ? "the root node" : "node '" + node->path() + "'";
    throw SceneError(where, component.typeName() + " '" + component.name() + "' needs a body, but " + place +
                                " holds no mechanical state (e.g. a DynamicSpline)");
  }
  try {
    component.bind(*body, *this);
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    // A library's own refusal (std::invalid_argument, a failed factorization): at its component.
    throw SceneError(component.origin(), component.typeName() + " cannot be set up: " + e.what());
  }
}

void Scene::init() {
  constraint_problem_.layout_revision = -1;  // bodies may come and go at init: rebuilt at the next solve
  if (!(settings_.dt > 0.0) || !std::isfinite(settings_.dt))
    throw SceneError(settings_.source + ": /dt", "a positive time step", std::to_string(settings_.dt));

  bodies_.clear();
  force_fields_.clear();
  constraints_.clear();
  layout_controllers_.clear();
  root_->collect(bodies_);
  root_->collect(force_fields_);
  root_->collect(constraints_);
  root_->collect(layout_controllers_);

  std::vector<Integrator*> integrators;
  std::vector<ConstraintSolver*> solvers;
  root_->collect(integrators);
  root_->collect(solvers);
  if (integrators.empty()) throw SceneError(settings_.source + ": /integrator", "an integrator in the scene", "none");
  if (integrators.size() > 1)
    throw SceneError(integrators[1]->origin(), "exactly one integrator in the scene (the one of /integrator)",
                     "a second one, " + integrators[1]->typeName());
  if (solvers.size() > 1)
    throw SceneError(solvers[1]->origin(), "at most one constraint solver (the one of /constraint_solver)",
                     "a second one, " + solvers[1]->typeName());
  integrator_ = integrators.front();
  constraint_solver_ = solvers.empty() ? nullptr : solvers.front();
  if (!constraints_.empty() && !constraint_solver_)
    throw SceneError(settings_.source + ": /constraint_solver", "a constraint solver since the scene has constraints",
                     "none");

  // Lay the bodies out in one state vector, in declaration order.
  point_count_ = 0;
  for (MechanicalState* body : bodies_) {
    body->setOffset(point_count_);
    point_count_ += body->pointCount();
  }
  state_.time = 0.0;
  state_.steps = 0;
  state_.q.resize(3 * point_count_);
  state_.v.setZero(3 * point_count_);
  for (MechanicalState* body : bodies_) body->block(state_.q) = body->initialPositions();

  for (ForceField* f : force_fields_) bindBodyComponent(*f);
  for (Constraint* c : constraints_) bindBodyComponent(*c);
  for (LayoutController* l : layout_controllers_) bindBodyComponent(*l);
  constraint_first_row_.assign(constraints_.size(), -1);
  setExtraIndices();
  setInternalOffsets();
  state_.q.conservativeResize(positionSize());
  state_.v.setZero(velocitySize());
  for (MechanicalState* body : bodies_) body->initialVelocities(body->block(state_.v));
  for (const Constraint* c : constraints_) c->initialExtra(state_.q);
  for (const MechanicalState* body : bodies_)
    body->initialInternalState(body->internalPositions(state_.q), body->internalVelocities(state_.v));
  if (hasInternalDofs() && !integrator_->internalDofsRefusal().empty())
    for (const MechanicalState* body : bodies_)
      if (body->internalVelocityCount() > 0 || body->internalPositionCount() > 0) {
        std::string expected = integrator_->internalDofsRefusal();
        expected += " for ";
        expected += body->describe();
        throw SceneError(body->origin(), expected, integrator_->typeName());
      }
  if (hasInternalDofs() && integrator_->needsJacobians())
    for (const MechanicalState* body : bodies_)
      if (!body->supportsImplicitInternal())
        throw SceneError(body->origin(),
                         "an explicit integrator for " + body->describe() +
                             " (its internal DOFs have no place in an implicit step's matrix)",
                         integrator_->typeName());
  for (Constraint* c : constraints_) c->updateRelease(state_);
  if (integrator_->needsJacobians())
    for (const ForceField* f : force_fields_)
      if (!f->hasJacobian())
        throw SceneError(f->origin(), integrator_->typeName() + " needs the force Jacobian of every force field, but " +
                                          f->describe() + " does not provide one (use an explicit integrator)");

  initCollision();
  resizeWorkspace();
  contact_halvings_ = 0;
  solve_halvings_ = 0;
  substeps_ = 0;
  state_.memory.substep_depth = 0;  // a fresh start takes whole steps first
  step_count_ = 0;
  initialized_ = true;
}

void Scene::setExtraIndices() {
  // Extra scalar DOFs of constraints (a sliding point's abscissa) after the 3N point
  // coordinates, in declaration order (scene_state.hpp); their velocities start at zero.
  extra_count_ = 0;
  for (Constraint* c : constraints_) {
    c->setExtraIndex(3 * point_count_ + extra_count_);
    extra_count_ += c->extraDofCount();
  }
}

void Scene::setInternalOffsets() {
  const int start = 3 * point_count_ + extra_count_;
  internal_position_count_ = 0;
  internal_velocity_count_ = 0;
  for (MechanicalState* body : bodies_) {
    body->setInternalOffsets(start + internal_position_count_, start + internal_velocity_count_);
    body->setInternalGroupOffset(point_count_ + internal_velocity_count_ / 3);  // step matrix groups (triples)
    internal_position_count_ += body->internalPositionCount();
    internal_velocity_count_ += body->internalVelocityCount();
  }
  internal_increment_.setZero(internal_velocity_count_);
}

void Scene::integratePositions(const VecX& q0, const VecX& w, double h, VecX& q1) const {
  // Points and extra DOFs: q + h w. Internal DOFs: each body's own q ⊕ h w.
  const Eigen::Index linear = 3 * Eigen::Index(point_count_) + extra_count_;
  if (&q1 != &q0) q1.resize(q0.size());
  q1.head(linear) = q0.head(linear) + h * w.head(linear);
  if (!hasInternalDofs()) return;
  for (const MechanicalState* body : bodies_) {
    const int nv = body->internalVelocityCount();
    if (nv == 0 && body->internalPositionCount() == 0) continue;
    auto increment = internal_increment_.head(nv);
    increment = h * body->internalVelocities(w);
    body->integrateInternal(body->internalPositions(q0), increment, body->internalPositions(q1));
  }
}

void Scene::bindComponents() {
  for (ForceField* f : force_fields_) bindBodyComponent(*f);
  for (Constraint* c : constraints_) bindBodyComponent(*c);
  for (LayoutController* l : layout_controllers_) bindBodyComponent(*l);
  const int extras = extra_count_;
  setExtraIndices();
  if (extra_count_ != extras)
    throw SceneError(settings_.source, std::to_string(extras) + " extra DOFs of constraints after a layout change",
                     std::to_string(extra_count_));
  for (Constraint* c : constraints_) c->updateRelease(state_);
  if (collision_) collision_->init(*this);
  resizeWorkspace();
}

void Scene::resizeWorkspace() {
  force_.setZero(velocitySize());
  last_good_ = state_;
  substep_start_.assign(kMaxContactHalvings + 1, state_);
}

void Scene::initCollision() {
  // Stage 2 runs only when the scene holds collision models (collision_pipeline.hpp).
  std::vector<CollisionModel*> collision_models;
  std::vector<CollisionPipeline*> pipelines;
  root_->collect(collision_models);
  root_->collect(pipelines);
  if (pipelines.size() > 1)
    throw SceneError(pipelines[1]->origin(), "at most one collision pipeline in the scene", std::to_string(pipelines.size()));
  collision_ = nullptr;
  if (!collision_models.empty()) {
    if (pipelines.empty())
      throw SceneError(settings_.source + ": /collision",
                       "a collision pipeline since the scene has collision models (e.g. \"collision\": {\"type\": "
                       "\"CollisionPipeline\"})",
                       "none");
    collision_ = pipelines.front();
    try {
      collision_->init(*this);
    } catch (const SceneError&) {
      throw;
    } catch (const std::exception& e) {
      throw SceneError(collision_->origin(), collision_->typeName() + " cannot be set up: " + e.what());
    }
    // Contacts as constraint rows need the constraint solver: the pipeline's own by default.
    if (!constraint_solver_ && collision_->addsContactRows()) constraint_solver_ = collision_->defaultConstraintSolver();
    if (integrator_->needsJacobians() && !collision_->hasJacobian())
      throw SceneError(collision_->origin(), integrator_->typeName() + " needs the contact force Jacobian, but " +
                                                 collision_->describe() + " does not provide one");
  }

}

std::string Scene::findNonFinite(const VecX& v) const {
  // v: a position (q) or velocity-layout vector; the internal blocks by its length.
  const bool positions = v.size() == positionSize();
  for (const MechanicalState* body : bodies_) {
    if (!body->block(v).allFinite()) return body->describe();
    const Eigen::Index first = positions ? body->internalPositionOffset() : body->internalVelocityOffset();
    const Eigen::Index count = positions ? body->internalPositionCount() : body->internalVelocityCount();
    if (count > 0 && !v.segment(first, count).allFinite()) return body->describe() + " (its internal DOFs)";
  }
  for (const Constraint* c : constraints_)
    if (c->extraDofCount() > 0 && !v.segment(c->extraIndex(), c->extraDofCount()).allFinite()) return c->describe();
  return "";
}

void Scene::computeForce(const SceneState& s, VecX& B) {
  // Stage 3a: accumulate generalized forces B (paper eq. 2): gravity and every force field.
  B.setZero(velocitySize());
  addForces(s, B, false);
  // One finiteness check per evaluation; only when it fails are the sources evaluated again one
  // by one, to name the first that produced a non-finite force (the step is rolled back anyway).
  if (fault_.empty() && !B.allFinite()) {
    VecX again = VecX::Zero(velocitySize());
    fault_ = addForces(s, again, true);
  }
}

std::string Scene::addForces(const SceneState& s, VecX& B, bool name_non_finite) const {
  // The sources in order; with name_non_finite, the first after which B is not finite is named.
  const auto failed = [&] { return name_non_finite && !B.allFinite(); };
  for (const MechanicalState* body : bodies_) {
    body->addGravity(settings_.gravity, body->block(B));
    if (failed()) return "gravity produced a non-finite force on " + body->describe();
    if (body->internalVelocityCount() > 0) body->addInternalForce(s, body->internalVelocities(B));
    if (failed()) return body->describe() + " produced a non-finite force on its internal DOFs";
  }
  for (const ForceField* field : force_fields_) {
    field->addForce(s, B);
    if (failed()) return field->describe() + " produced a non-finite force";
  }
  // Contact penalties of the step's contact set (stage 2 detected it).
  if (collision_) {
    collision_->addForce(s, B);
    if (failed()) return collision_->describe() + " produced a non-finite contact force";
  }
  // Known constraint forces (friction along a sliding point's tangent).
  for (const Constraint* c : constraints_) {
    if (c->active()) c->addForce(s, B);
    if (failed()) return c->describe() + " produced a non-finite force";
  }
  return name_non_finite ? "the forces are not finite, although no source alone made them so" : "";
}

Eigen::Ref<const VecX> Scene::constraintMultipliers(const Constraint& constraint) const {
  static const VecX none;
  if (!constraint_solver_) return none;
  const auto found = std::find(constraints_.begin(), constraints_.end(), &constraint);
  if (found == constraints_.end()) return none;
  const int first = constraint_first_row_[found - constraints_.begin()];
  const Eigen::Ref<const VecX> lambda = constraint_solver_->multipliers();
  if (first < 0 || first + constraint.rowCount() > lambda.size()) return none;
  return lambda.segment(first, constraint.rowCount());
}

void Scene::applyConstraints(const SceneState& s, const BlockInverse& inverse, VecX& a) {
  // Stage 3c: constrained accelerations (paper §4, acceleration decomposition): the active
  // constraints' rows, then the step's unilateral contacts as inequality rows, solved together
  // by the one constraint solver.
  if (!constraint_solver_) return;
  const StageTimer timer(stage_times_.constraint_solve);
  rows_.clear();
  for (std::size_t i = 0; i < constraints_.size(); ++i) {
    const Constraint* c = constraints_[i];
    constraint_first_row_[i] = c->active() ? rows_.rows() : -1;
    if (c->active()) c->buildRows(s, rows_);
  }
  const int first_contact_row = rows_.rows();
  const int contact_rows = collision_ ? collision_->addContactRows(s, rows_) : 0;
  if (rows_.rows() > 0) constraint_solver_->solve(constraintProblem(), rows_, inverse, a);
  if (contact_rows > 0) collision_->takeMultipliers(constraint_solver_->multipliers(), first_contact_row);
  // Stage 3d: accelerations of the constraints' extra DOFs (a sliding point's s̈ by the direct
  // relation of [Lenoir talk 2008]), from the constrained point accelerations.
  if (extra_count_ > 0 && a.size() == velocitySize())
    for (const Constraint* c : constraints_)
      if (c->extraDofCount() > 0) c->extraAcceleration(s, a);
  if (fault_.empty() && !a.allFinite()) fault_ = constraint_solver_->describe() +
                  " produced non-finite accelerations (redundant or conflicting constraints, such as two at one point "
                  "of a body, make its system singular)";
}

void Scene::computeAcceleration(const SceneState& s, VecX& a) {
  computeForce(s, force_);
  // Stage 3b: tendency accelerations A_t = M⁻¹ B, one banded solve per body (paper eq. 3);
  // a also holds the extra DOFs after the points (scene_state.hpp), set by applyConstraints.
  a = force_;  // velocity layout: points, extra DOFs (no force: set by applyConstraints), internal DOFs
  a.segment(3 * point_count_, extra_count_).setZero();
  for (const MechanicalState* body : bodies_) {
    body->solveMass(body->block(a));
    if (body->internalVelocityCount() > 0) body->solveInternalMass(body->internalVelocities(a));
  }
  applyConstraints(s, mass_inverse_, a);
}

void Scene::addForceJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out,
                             JacobianTerms terms) const {
  // Gravity is constant: only the force fields contribute to K = ∂Q/∂q and D = ∂Q/∂q̇.
  for (const ForceField* field : force_fields_) {
    const bool constant = field->jacobianIsConstant();
    if (terms == JacobianTerms::kAll || constant == (terms == JacobianTerms::kConstant))
      field->addJacobian(s, k_factor, d_factor, out);
  }
  if (collision_ && terms != JacobianTerms::kConstant) collision_->addJacobian(s, k_factor, d_factor, out);
}

void Scene::addMassMatrix(double factor, JacobianAccumulator& out) const {
  for (const MechanicalState* body : bodies_) {
    body->addMassMatrix(factor, out);
    if (body->internalVelocityCount() > 0) body->addInternalMassMatrix(factor, out);
  }
}

StepReport Scene::step() {
  if (!initialized_) init();
  const FlushDenormals flush_denormals;  // subnormals made long threads' band solves up to 16× slower
  StepReport report;
  report.step = step_count_;
  report.time = state_.time;
  beginStep();
  try {
    if (fault_.empty()) advanceStep(settings_.dt);
  } catch (const std::exception& e) {
    // A numerical routine that refused its input (a non-finite query point, a resampling
    // beyond its limit): a fault of the step like any other, rolled back by endStep.
    // The routine does not say which component called it: the scene file is the place.
    if (fault_.empty()) fault_ = settings_.source + ": the step failed: " + e.what();
  }
  return endStep(report);
}

void Scene::beginStep() {
  fault_.clear();
  {
    const StageTimer timer(stage_times_.layout);
    applyScheduledLayoutChanges();
    applyRuptures();
    if (fault_.empty() && !layout_controllers_.empty()) applyLayoutControllers();
  }
  // endStep needs the last good state: copied into preallocated storage (no allocation).
  last_good_ = state_;
  // Scheduled releases (cuts) take effect at the first step that starts at or after their time.
  for (Constraint* c : constraints_) c->updateRelease(state_);
  if (constraint_solver_) constraint_solver_->beginStep();
}

void Scene::applyScheduledLayoutChanges() {
  // Control points scheduled for insertion, and cuts, at the step that starts nearest their
  // time (half a step of slack absorbs the round-off of t = steps · dt); a layout change may
  // allocate.
  for (MechanicalState* body : bodies_)
    if (CurveBody* curve = body->curve())
      while (const CurveBody::LayoutChange* due = curve->layoutChangeDue(state_.time + 0.5 * settings_.dt)) {
        const CurveBody::LayoutChange change = *due;
        curve->markLayoutChangeApplied();
        const bool cutting = change.kind == CurveBody::LayoutChange::Kind::kCut;
        try {
          if (cutting)
            cut(*curve, change.abscissas.front());
          else
            refine(*curve, change.abscissas);
        } catch (const std::exception& e) {
          // CurveBody::refine and cut throw before they change anything: the state is still the
          // last good one, and the step reports the fault.
          noteFault(settings_.source + ": a scheduled " + (cutting ? "cut" : "refinement") + " failed: " + e.what());
          return;
        }
      }
}

void Scene::applyLayoutControllers() {
  for (LayoutController* controller : layout_controllers_) {
    if (!controller->due(state_.steps)) continue;
    CurveBody* curve = controller->body().curve();
    if (!curve) continue;
    plan_.insert.clear();
    plan_.remove.clear();
    controller->plan(*this, plan_);
    try {
      if (!plan_.insert.empty()) {
        refine(*curve, plan_.insert);
        adaptive_insertions_ += static_cast<long>(plan_.insert.size());
      }
      // Removals one by one, each refused by the curve when it would move it further than the
      // tolerance (the knots planned stay knots when insertions come first: they are apart).
      for (const double s : plan_.remove) {
        if (coarsen(*curve, s, plan_.tolerance))
          ++adaptive_removals_;
        else
          controller->removalRefused(s);
      }
    } catch (const std::exception& e) {
      // refine and coarsen throw before they change the body (CurveBody::refine, coarsen); a
      // component that cannot be bound to the new layout throws after it: the step reports it.
      noteFault(controller->describe() + ": an adaptive layout change failed: " + e.what());
      return;
    }
  }
}

void Scene::actingAbscissas(const MechanicalState& body, std::vector<double>& out) const {
  for (const ForceField* f : force_fields_)
    if (&f->body() == &body) f->actingAbscissas(state_, out);
  for (const Constraint* c : constraints_)
    if (&c->body() == &body) c->actingAbscissas(state_, out);
  if (collision_) collision_->contactAbscissas(body, out);
}

void Scene::applyRuptures() {
  // One tear per body and step at most: its tension is measured again after the cut's step.
  for (ForceField* field : force_fields_) {
    double s = 0.0, tension = 0.0;
    if (!field->tearsAt(state_, s, tension)) continue;
    CurveBody* curve = field->body().curve();
    if (!curve) continue;
    try {
      cut(*curve, s);
    } catch (const std::exception& e) {
      std::string message = field->describe();
      message += ": the thread tore at s = ";
      message += std::to_string(s);
      message += " but cannot be cut there: ";
      message += e.what();
      noteFault(message);
      return;
    }
    ruptures_.push_back({state_.time, curve->describe(), s, tension});
    return;  // the cut laid the scene out anew: the fields are bound again, checked next step
  }
}

long Scene::unconvergedContactSolves() const {
  if (!constraint_solver_) return 0;
  const ContactSolveTally& tally = constraint_solver_->contactTally();
  return tally.solves - tally.converged;
}

void Scene::advanceStep(double dt) {
  // Step-size memory, as an adaptive integrator starts from its last accepted step (Hairer,
  // Nørsett & Wanner, Solving ODEs I, §II.4): a step begins as 2^d sub-steps of dt / 2^d, d the
  // depth the last step needed, rather than at dt, to be halved again d times. While a thread
  // runs through a knot every 1 ms step needs 1/8 ms sub-steps: from dt, that is 1 + 2 + 4
  // attempts thrown away for 8 kept. The depth then comes back by one level per step taken
  // without a halving, so a scene that stops needing short sub-steps returns to dt in d steps.
  // The depth remembered is at most kMaxRememberedDepth (dt / 8): a rare deeper halving (a
  // pass-through caught at dt / 64) then costs the next steps 8 + 4 + 2 sub-steps, not 64 + 32 + ….
  const int start = std::clamp(state_.memory.substep_depth, 0, kMaxRememberedDepth);
  deepest_depth_ = start;
  const int count = 1 << start;
  const double h = dt / static_cast<double>(count);
  for (int k = 0; k < count && fault_.empty(); ++k) advance(h, start);
  // The next step's start, in the state: a step that fails is rolled back with the depth it
  // began with (endStep restores the last good state).
  if (fault_.empty())
    state_.memory.substep_depth =
        deepest_depth_ > start ? std::min(deepest_depth_, kMaxRememberedDepth) : std::max(0, start - 1);
}

void Scene::advance(double h, int depth) {
  ++substeps_;
  deepest_depth_ = std::max(deepest_depth_, depth);
  {
    const StageTimer timer(stage_times_.detection);
    detectCollisions(h);
  }
  substep_start_[depth] = state_;  // preallocated: no allocation
  const long unconverged = unconvergedContactSolves();
  {
    // The constraint solves inside the step count as theirs (applyConstraints): taken out here.
    const double solves_before = stage_times_.constraint_solve;
    const StageTimer timer(stage_times_.integration);
    integrate(h);
    stage_times_.integration -= stage_times_.constraint_solve - solves_before;
  }
  if (!fault_.empty() || !collision_) return;
  // A contact solve that did not reach its tolerance (constraint_solver.hpp's tally): the step
  // is redone in halves, down to dt / 2^kMaxSolveHalvings — a shorter step moves the contacts less
  // from the state their rows were built at, and its Newton starts nearer its solution. At the
  // finest sub-step the best iterate is kept; the tally reports it.
  const bool solve_failed = unconvergedContactSolves() > unconverged && depth < kMaxSolveHalvings;
  CollisionPipeline::Miss miss = CollisionPipeline::Miss::kNone;
  {
    const StageTimer timer(stage_times_.missed_contact);
    miss = collision_->missedContact(state_);
  }
  if (miss == CollisionPipeline::Miss::kNone && !solve_failed) return;
  if (miss == CollisionPipeline::Miss::kNone) {
    ++solve_halvings_;
    redoInHalves(h, depth);
    return;
  }
  // The contact set of the start did not hold the motion (a strand moved through another, or
  // deep into it, within the step): redo it as two halves, each with its own detection (Bridson
  // et al. 2002 stop a step at the first such event; halving keeps the step pipeline as it is).
  if (depth == kMaxContactHalvings) {
    // A deep penetration at the finest sub-step is kept (Baumgarte's term pushes it out in the
    // next steps); a pass-through is not: the threads' topology changed.
    if (miss == CollisionPipeline::Miss::kPassThrough)
      noteFault(collision_->describe() + ": a thread passed through another even in " +
                std::to_string(1 << depth) + " sub-steps of " + std::to_string(h) + " s");
    if (miss == CollisionPipeline::Miss::kTooFar)
      noteFault(collision_->describe() + ": the bodies swept so far that contact detection found more candidate "
                "pairs than its budget, even in " + std::to_string(1 << depth) + " sub-steps of " +
                std::to_string(h) + " s");
    return;
  }
  ++contact_halvings_;
  redoInHalves(h, depth);
}

void Scene::redoInHalves(double h, int depth) {
  state_ = substep_start_[depth];
  advance(0.5 * h, depth + 1);
  if (fault_.empty()) advance(0.5 * h, depth + 1);
}

void Scene::detectCollisions(double h) {
  // Only when collision models exist.
  if (collision_) collision_->beginStep(*this, state_, h);
  for (ForceField* field : force_fields_) field->beginStep(state_, h);
}

void Scene::integrate(double h) { integrator_->step(*this, state_, h); }

StepReport Scene::endStep(StepReport report) {
  std::string culprit = fault_;
  if (culprit.empty() && !state_.allFinite()) {
    const std::string body = findNonFinite(state_.v).empty() ? findNonFinite(state_.q) : findNonFinite(state_.v);
    culprit = (body.empty() ? std::string("the scene") : body) + " has non-finite positions or velocities";
  }
  // Speeds of points only: extra DOFs (abscissas) have other units.
  if (culprit.empty() && point_count_ > 0 && state_.v.head(3 * point_count_).cwiseAbs().maxCoeff() > settings_.max_speed) {
    Eigen::Index i = 0;
    state_.v.head(3 * point_count_).cwiseAbs().maxCoeff(&i);
    for (const MechanicalState* body : bodies_)
      if (i / 3 >= body->offset() && i / 3 < body->offset() + body->pointCount())
        culprit = body->describe() + " moves faster than max_speed = " + std::to_string(settings_.max_speed) +
                  " m/s (point " + std::to_string(i / 3 - body->offset()) + ")";
  }
  if (!culprit.empty()) {
    state_ = last_good_;
    restoreMemory();  // the components as they were too: the failed step's factors and forces are not kept
    report.ok = false;
    report.culprit = culprit;
    report.message = "diverged at step " + std::to_string(report.step) + " (t = " + std::to_string(report.time) +
                     " s): " + culprit + "; state rolled back to t = " + std::to_string(state_.time) + " s";
    return report;
  }
  ++step_count_;
  state_.time = static_cast<double>(++state_.steps) * settings_.dt;
  saveMemory();
  return report;
}

void Scene::MassInverse::solveBlock(int body, Eigen::Ref<VecX> x) const {
  const MechanicalState& b = *scene_.bodies_[body];
  b.solveMass(PointsMap(x.data(), b.pointCount(), 3));
}

int Scene::bodyOfPoint(int p) const {
  int k = static_cast<int>(bodies_.size()) - 1;
  while (k > 0 && bodies_[k]->offset() > p) --k;
  return k;
}

Energy Scene::energy(const SceneState& s) const {
  Energy e;
  for (const MechanicalState* body : bodies_) {
    e.kinetic += body->kineticEnergy(body->block(s.v));
    e.potential += body->gravityPotential(settings_.gravity, body->block(s.q));
    if (body->internalVelocityCount() > 0) {  // ½ vᵀ M v of the internal DOFs
      auto mv = internal_increment_.head(body->internalVelocityCount());  // a workspace sized by init
      body->multiplyInternalMass(body->internalVelocities(s.v), mv);
      e.kinetic += 0.5 * body->internalVelocities(s.v).dot(mv);
    }
  }
  for (const ForceField* field : force_fields_) e.potential += field->potentialEnergy(s);
  return e;
}

VecX Scene::constraintViolation(const SceneState& s) const {
  int rows = 0;
  for (const Constraint* c : constraints_)
    if (c->active()) rows += c->violationCount();
  VecX g(rows);
  int first = 0;
  for (const Constraint* c : constraints_) {
    if (!c->active()) continue;
    c->violation(s, g, first);
    first += c->violationCount();
  }
  return g;
}

namespace {
/// Refining or coarsening maps points only: a body with internal DOFs per point is refused.
void requirePointsOnly(const CurveBody& body, const char* what) {
  if (body.internalVelocityCount() > 0 || body.internalPositionCount() > 0)
    throw SceneError(body.origin(), std::string("a body of points only to ") + what,
                     body.describe() + ", which has internal DOFs (their map is not defined)");
}
}  // namespace

void Scene::refine(CurveBody& body, const std::vector<double>& abscissas) {
  if (!initialized_) init();
  requirePointsOnly(body, "insert control points into");
  const SparseMatrix A = body.refine(abscissas);  // throws before changing anything
  relayout(body, A);
}

void Scene::cut(CurveBody& body, double abscissa) {
  if (!initialized_) init();
  requirePointsOnly(body, "cut");
  const SparseMatrix A = body.cut(abscissa);  // throws before changing anything
  relayout(body, A);
}

bool Scene::coarsen(CurveBody& body, double abscissa, double tolerance) {
  if (!initialized_) init();
  requirePointsOnly(body, "remove control points from");
  // Linear momentum before: p = ∫ρA Ṗ ds = 1ᵀ M v per axis (the basis is a partition of unity).
  Points mv(body.pointCount(), 3);
  body.multiplyMass(body.block(state_.v), mv);
  const Vec3 momentum = mv.colwise().sum().transpose();
  const SparseMatrix R = body.coarsen(abscissa, body.block(state_.q), tolerance);
  if (R.rows() == 0) return false;  // the curve would move further than the tolerance
  relayout(body, R);
  // ṽ = R v is a least-squares fit and need not keep p. The smallest change of ṽ in the kinetic
  // energy's norm, ½ δvᵀ M̃ δv, with 1ᵀ M̃ (ṽ + δv) = p is a uniform velocity δv = u (a partition
  // of unity represents it exactly): u = (p − 1ᵀ M̃ ṽ) / m, m = 1ᵀ M̃ 1 the body's mass.
  const int n = body.pointCount();
  Points fitted(n, 3), ones = Points::Ones(n, 3);
  body.multiplyMass(body.block(state_.v), fitted);
  Points mass(n, 3);
  body.multiplyMass(ones, mass);
  const Vec3 u = (momentum - fitted.colwise().sum().transpose()) / mass.col(0).sum();
  body.block(state_.v).rowwise() += u.transpose();
  return true;
}

void Scene::relayout(const CurveBody& body, const SparseMatrix& A) {
  if (A.rows() != body.pointCount())
    throw SceneError(body.origin(), "a layout map with one row per new point (" + std::to_string(body.pointCount()) + ")",
                     std::to_string(A.rows()) + " rows");
  // The old layout, to carry the state over: state_ and the offsets are still those of before
  // the body changed its points (a layout change may allocate).
  const SceneState old = state_;
  const int old_extras = 3 * point_count_;
  // The step memory of the old layout: no kept matrix (the integrator assembles anew), and the
  // current layout's revision (a state taken now restores into this layout).
  state_.memory.matrix_id = 0;
  std::vector<int> old_offsets, old_internal_q, old_internal_v;
  for (const MechanicalState* b : bodies_) {
    old_offsets.push_back(b->offset());
    old_internal_q.push_back(b->internalPositionOffset());
    old_internal_v.push_back(b->internalVelocityOffset());
  }
  point_count_ = 0;
  for (MechanicalState* b : bodies_) {
    b->setOffset(point_count_);
    point_count_ += b->pointCount();
  }
  setInternalOffsets();
  state_.q.resize(positionSize());
  state_.v.resize(velocitySize());
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    MechanicalState* b = bodies_[k];
    const int n = b == &body ? static_cast<int>(A.cols()) : b->pointCount();
    const ConstPointsMap q(old.q.data() + 3 * old_offsets[k], n, 3), v(old.v.data() + 3 * old_offsets[k], n, 3);
    if (b == &body) {
      b->block(state_.q) = A * q;  // q̃ = A q: the same curve (refine) or its fit (coarsen)
      b->block(state_.v) = A * v;  // ṽ = A v: the velocity field the same way
    } else {
      b->block(state_.q) = q;
      b->block(state_.v) = v;
    }
  }
  // Abscissas: s is kept by both. Internal DOFs of the other bodies: carried over as they are
  // (Scene::refine and coarsen refuse a body that has its own).
  state_.q.segment(3 * point_count_, extra_count_) = old.q.segment(old_extras, extra_count_);
  state_.v.segment(3 * point_count_, extra_count_) = old.v.segment(old_extras, extra_count_);
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    const MechanicalState* b = bodies_[k];
    b->internalPositions(state_.q) = old.q.segment(old_internal_q[k], b->internalPositionCount());
    b->internalVelocities(state_.v) = old.v.segment(old_internal_v[k], b->internalVelocityCount());
  }
  ++layout_revision_;
  state_.memory.layout_revision = layout_revision_;
  bindComponents();
}

void Scene::setState(const SceneState& s) {
  if (s.q.size() != state_.q.size() || s.v.size() != state_.v.size())
    throw SceneError(settings_.source, "a state of " + std::to_string(state_.q.size()) +
                                           " coordinates (the scene's current layout)",
                     std::to_string(s.q.size()) + " (a state saved before the points changed?)");
  // Same size is not same layout: points inserted and removed since leave the count as it was.
  if (s.memory.layout_revision >= 0 && s.memory.layout_revision != layout_revision_)
    throw SceneError(settings_.source, "a state of the scene's current layout (layout revision " +
                                           std::to_string(layout_revision_) + ")",
                     "a state saved at layout revision " + std::to_string(s.memory.layout_revision) +
                         " (points were inserted, removed or cut since)");
  if (s.memory.matrix_id != 0 &&
      (s.memory.matrix_q.size() != s.q.size() || s.memory.matrix_v.size() != s.v.size()))
    throw SceneError(settings_.source, "a state whose step memory has the state's size",
                     "a kept step matrix of another size (a state put together by hand?)");
  state_ = s;
  // Releases are a function of the state: restoring a state before a cut restores the rows.
  for (Constraint* c : constraints_) c->updateRelease(state_);
  // What the next step reads beyond q and v (StepMemory): the run from here is the one that first
  // left this state, bit for bit.
  restoreMemory();
}

void Scene::saveMemory() {
  state_.memory.layout_revision = layout_revision_;
  if (collision_) collision_->saveMemory(state_.memory);
  if (constraint_solver_) constraint_solver_->saveMemory(state_.memory);
  integrator_->saveMemory(state_.memory);
}

void Scene::restoreMemory() {
  if (collision_) collision_->restoreMemory(state_.memory);
  if (constraint_solver_) constraint_solver_->restoreMemory(state_.memory);
  integrator_->restoreMemory(*this, state_.memory);
}

const ConstraintProblem& Scene::constraintProblem() const {
  ConstraintProblem& p = constraint_problem_;
  if (p.layout_revision == layout_revision_ && p.dof_points == point_count_ && p.state_size == state_.q.size() &&
      p.bodies.size() == bodies_.size())
    return p;
  p.bodies.clear();
  for (const MechanicalState* body : bodies_) p.bodies.push_back({body->offset(), body->pointCount()});
  p.dof_points = point_count_;
  p.state_size = state_.q.size();
  p.internal_dofs = hasInternalDofs();
  p.layout_revision = layout_revision_;
  return p;
}

}  // namespace filum
