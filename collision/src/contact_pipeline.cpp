#include "filum/collision/contact_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "filum/core/node.hpp"
#include "filum/core/scene.hpp"

namespace filum::collision {

std::unique_ptr<ContactPipeline> ContactPipeline::fromParams(const Params& p) {
  Settings s;
  const std::string response = p.string("response", "penalty");
  if (response == "unilateral") {
    s.response = Response::kUnilateral;
  } else if (response != "penalty") {
    p.fail("response", "\"penalty\" or \"unilateral\"");
  }
  s.penalty.stiffness = p.positive("stiffness", s.penalty.stiffness);
  s.penalty.damping = p.nonNegative("damping", s.penalty.damping);
  s.penalty.friction_velocity = p.positive("friction_velocity", s.penalty.friction_velocity);
  s.friction = p.nonNegative("friction", s.friction);
  s.margin = p.nonNegative("margin", s.margin);
  s.continuous = p.boolean("continuous", s.continuous);
  s.cell_size = p.nonNegative("cell_size", s.cell_size);
  s.unilateral.stabilization = p.positive("stabilization", 0.0);
  s.unilateral.friction_rate = p.positive("friction_rate", 0.0);
  s.unilateral.iterations = p.integer("iterations", 1, s.unilateral.iterations);
  s.unilateral.tolerance = p.positive("tolerance", s.unilateral.tolerance);
  return std::make_unique<ContactPipeline>(s);
}

void ContactPipeline::init(const Scene& scene) {
  models_.clear();
  obstacles_.clear();
  scene.root().collect(models_);
  scene.root().collect(obstacles_);
  for (SphereCollisionModel* m : models_) m->init(scene);
  time_step_ = scene.settings().dt;
  // Margin: contacts are kept up to half the smallest radius of gap (beyond the sweep).
  double smallest = std::numeric_limits<double>::infinity();
  for (const SphereCollisionModel* m : models_) smallest = std::min(smallest, m->radius());
  margin_ = settings_.margin >= 0.0 ? settings_.margin : (std::isfinite(smallest) ? 0.5 * smallest : 0.0);
  // Baumgarte ω of contact rows: critically damped over two steps by default.
  unilateral_ = settings_.unilateral;
  if (!(unilateral_.stabilization > 0.0)) unilateral_.stabilization = 0.5 / time_step_;
  if (!(unilateral_.friction_rate > 0.0)) unilateral_.friction_rate = unilateral_.stabilization;
  broad_phase_ = UniformGridBroadPhase(settings_.cell_size);
  contacts_.clear();
  solver_.resetWarmStart();
}

void ContactPipeline::beginStep(const Scene& /*scene*/, const SceneState& s) {
  // 1. Spheres on the current curves, centres and velocities mapped down.
  stats_ = Statistics();
  for (SphereCollisionModel* m : models_) {
    m->update(s);
    stats_.spheres += m->sphereCount();
  }
  for (Obstacle* o : obstacles_) o->moveTo(s.time);
  contacts_.clear();
  solver_.resetWarmStart();

  NarrowPhaseSettings narrow;
  narrow.margin = margin_;
  narrow.time_step = settings_.continuous ? time_step_ : 0.0;
  narrow.friction = settings_.friction;
  narrow.time = s.time;

  // 2. Thread–obstacle contacts, sphere by sphere.
  const int model_count = static_cast<int>(models_.size());
  for (int m = 0; m < model_count; ++m)
    for (int o = 0; o < static_cast<int>(obstacles_.size()); ++o)
      findObstacleContacts(*models_[m], m, *obstacles_[o], o, narrow, contacts_);
  stats_.obstacle_contacts = static_cast<int>(contacts_.size());

  // 3. Thread–thread: chords in bounding spheres of their start and predicted end positions.
  chords_.clear();
  chord_owner_.clear();
  const double h = narrow.time_step;
  for (int m = 0; m < model_count; ++m) {
    const SphereCollisionModel& model = *models_[m];
    if (model_count == 1 && !model.selfCollision()) continue;
    const Points& x = model.centers();
    const Points& v = model.velocities();
    for (int k = 0; k + 1 < model.sphereCount(); ++k) {
      const Vec3 a0 = x.row(k).transpose(), a1 = x.row(k + 1).transpose();
      const Vec3 b0 = a0 + h * v.row(k).transpose(), b1 = a1 + h * v.row(k + 1).transpose();
      BoundingSphere bound;
      bound.center = 0.25 * (a0 + a1 + b0 + b1);
      const double reach = std::max({(a0 - bound.center).norm(), (a1 - bound.center).norm(),
                                     (b0 - bound.center).norm(), (b1 - bound.center).norm()});
      bound.radius = reach + model.radius() + 0.5 * margin_;
      chords_.push_back(bound);
      chord_owner_.emplace_back(m, k);
    }
  }
  stats_.chords = static_cast<int>(chords_.size());
  if (chords_.size() >= 2) {
    broad_phase_.findPairs(chords_, pairs_);
    stats_.candidate_pairs = static_cast<int>(pairs_.size());
    for (const IndexPair& pair : pairs_) {
      const auto [ma, k] = chord_owner_[pair.first];
      const auto [mb, l] = chord_owner_[pair.second];
      if (ma == mb) {
        const SphereCollisionModel& model = *models_[ma];
        if (!model.selfCollision()) continue;
        // Every point of chords k and l is closer than (|k − l| + 1) h along the curve.
        if ((std::abs(k - l) + 1) * model.mapping().spacing() < model.exclusion()) continue;
      }
      findChordContact(*models_[ma], ma, k, *models_[mb], mb, l, narrow, contacts_);
    }
  }
  stats_.thread_contacts = static_cast<int>(contacts_.size()) - stats_.obstacle_contacts;
}

void ContactPipeline::addForce(const SceneState& s, VecX& B) const {
  if (settings_.response != Response::kPenalty) return;
  // B += J_cᵀ F_c for every contact of the step, at the stage state s.
  for (const Contact& c : contacts_) {
    const ContactKinematics k = contactKinematics(c, s);
    if (k.gap >= 0.0) continue;
    addContactForce(c, penaltyForce(c, k, settings_.penalty).force, B);
  }
}

void ContactPipeline::addJacobian(const SceneState& s, double k_factor, double d_factor,
                                  JacobianAccumulator& out) const {
  if (settings_.response != Response::kPenalty) return;
  for (const Contact& c : contacts_) {
    const ContactKinematics k = contactKinematics(c, s);
    if (k.gap < 0.0) addPenaltyJacobian(c, k, settings_.penalty, k_factor, d_factor, out);
  }
}

bool ContactPipeline::solveContacts(const Scene& scene, const SceneState& s, const ConstraintRows& bilateral,
                                    const BlockInverse& inverse, VecX& a) {
  if (settings_.response != Response::kUnilateral || contacts_.empty()) return false;
  solver_.solve(scene, s, bilateral, contacts_, inverse, unilateral_, a);
  return true;
}

Vec3 ContactPipeline::contactForce(int i, const SceneState& s) const {
  if (settings_.response == Response::kUnilateral) {
    const auto& forces = solver_.contactForces();
    return i < static_cast<int>(forces.size()) ? forces[i] : Vec3::Zero();
  }
  const Contact& c = contacts_[i];
  return penaltyForce(c, contactKinematics(c, s), settings_.penalty).force;
}

Vec3 ContactPipeline::obstacleForce(int o, const SceneState& s) const {
  // Action and reaction: the obstacle receives −F of every contact it takes part in.
  Vec3 sum = Vec3::Zero();
  for (int i = 0; i < static_cast<int>(contacts_.size()); ++i)
    if (contacts_[i].obstacle == o) sum -= contactForce(i, s);
  return sum;
}

}  // namespace filum::collision
