#include "filum/core/scene.hpp"

#include <cmath>

#include "filum/core/scene_error.hpp"

namespace filum {

Scene::Scene() : root_(std::make_unique<Node>("root")) {}

MechanicalState* Scene::bodyAt(const std::string& path) {
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
  component.bind(*body, *this);
}

void Scene::init() {
  if (!(settings_.dt > 0.0) || !std::isfinite(settings_.dt))
    throw SceneError(settings_.source + ": /dt", "a positive time step", std::to_string(settings_.dt));

  bodies_.clear();
  force_fields_.clear();
  constraints_.clear();
  root_->collect(bodies_);
  root_->collect(force_fields_);
  root_->collect(constraints_);

  std::vector<Integrator*> integrators;
  std::vector<ConstraintSolver*> solvers;
  root_->collect(integrators);
  root_->collect(solvers);
  if (integrators.size() != 1)
    throw SceneError(settings_.source, "exactly one integrator in the scene",
                     std::to_string(integrators.size()));
  integrator_ = integrators.front();
  constraint_solver_ = solvers.empty() ? nullptr : solvers.front();
  if (!constraints_.empty() && !constraint_solver_)
    throw SceneError(settings_.source, "a constraint solver since the scene has constraints", "none");

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

  force_.setZero(3 * point_count_);
  last_good_ = state_;
  step_count_ = 0;
  initialized_ = true;
}

std::string Scene::findNonFinite(const VecX& v) const {
  for (const MechanicalState* body : bodies_)
    if (!body->block(v).allFinite()) return body->describe();
  return "";
}

void Scene::computeAcceleration(const SceneState& s, VecX& a) {
  // Stage 3a: accumulate generalized forces B (paper eq. 2): gravity and every force field.
  force_.setZero();
  for (const MechanicalState* body : bodies_) body->addGravity(settings_.gravity, body->block(force_));
  for (const ForceField* field : force_fields_) {
    field->addForce(s, force_);
    if (fault_.empty() && !force_.allFinite()) fault_ = field->describe() + " produced a non-finite force";
  }

  // Stage 3b: tendency accelerations A_t = M⁻¹ B, one banded solve per body (paper eq. 3).
  a = force_;
  for (const MechanicalState* body : bodies_) body->solveMass(body->block(a));

  // Stage 3c: constrained accelerations (paper §4, acceleration decomposition).
  if (constraint_solver_) {
    rows_.clear();
    for (const Constraint* c : constraints_)
      if (c->active()) c->buildRows(s, rows_);
    if (rows_.rows() > 0) constraint_solver_->solve(*this, rows_, mass_inverse_, a);
    if (fault_.empty() && !a.allFinite())
      fault_ = constraint_solver_->describe() + " produced non-finite accelerations";
  }
}

StepReport Scene::step() {
  if (!initialized_) init();
  StepReport report;
  report.step = step_count_;
  report.time = state_.time;

  // Stage 4 needs the last good state: copy into preallocated storage (no allocation).
  last_good_ = state_;
  fault_.clear();
  integrator_->step(*this, state_, settings_.dt);

  std::string culprit = fault_;
  if (culprit.empty() && !state_.allFinite()) {
    const std::string body = findNonFinite(state_.v).empty() ? findNonFinite(state_.q) : findNonFinite(state_.v);
    culprit = (body.empty() ? std::string("the scene") : body) + " has non-finite positions or velocities";
  }
  if (culprit.empty() && state_.v.cwiseAbs().maxCoeff() > settings_.max_speed) {
    Eigen::Index i = 0;
    state_.v.cwiseAbs().maxCoeff(&i);
    for (const MechanicalState* body : bodies_)
      if (i / 3 >= body->offset() && i / 3 < body->offset() + body->pointCount())
        culprit = body->describe() + " moves faster than max_speed = " + std::to_string(settings_.max_speed) +
                  " m/s (point " + std::to_string(i / 3 - body->offset()) + ")";
  }
  if (!culprit.empty()) {
    state_ = last_good_;
    report.ok = false;
    report.culprit = culprit;
    report.message = "diverged at step " + std::to_string(report.step) + " (t = " + std::to_string(report.time) +
                     " s): " + culprit + "; state rolled back to t = " + std::to_string(state_.time) + " s";
    return report;
  }
  ++step_count_;
  state_.time = static_cast<double>(++state_.steps) * settings_.dt;
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
  }
  for (const ForceField* field : force_fields_) e.potential += field->potentialEnergy(s);
  return e;
}

VecX Scene::constraintViolation(const SceneState& s) const {
  int rows = 0;
  for (const Constraint* c : constraints_)
    if (c->active()) rows += c->rowCount();
  VecX g(rows);
  int first = 0;
  for (const Constraint* c : constraints_) {
    if (!c->active()) continue;
    c->violation(s, g, first);
    first += c->rowCount();
  }
  return g;
}

}  // namespace filum
