#include "filum/collision/contact_pipeline.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <tuple>

#include "filum/collision/segment_closest_points.hpp"
#include "filum/collision/segment_continuous_collision.hpp"
#include "filum/constraints/projected_point_constraint.hpp"
#include "filum/core/node.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::collision {

namespace {

/// A sphere holding the chord [a0, a1] at the start of a step, [b0, b1] at its end (and so every
/// linear motion in between), grown by `pad`.
BoundingSphere sweptChordBound(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double pad) {
  BoundingSphere bound;
  bound.center = 0.25 * (a0 + a1 + b0 + b1);
  bound.radius = std::max({(a0 - bound.center).norm(), (a1 - bound.center).norm(), (b0 - bound.center).norm(),
                           (b1 - bound.center).norm()}) +
                 pad;
  return bound;
}

}  // namespace

std::unique_ptr<ContactPipeline> ContactPipeline::fromParams(const Params& p) {
  Settings s;
  const std::string response = p.string("response", "penalty");
  if (response == "unilateral") {
    s.response = Response::kUnilateral;
  } else if (response != "penalty") {
    p.fail("response", "\"penalty\" or \"unilateral\"");
  }
  s.penalty.stiffness = p.positive({"stiffness", "N/m"}, s.penalty.stiffness);
  s.penalty.damping = p.nonNegative({"damping", "N·s/m"}, s.penalty.damping);
  s.penalty.friction_velocity = p.positive({"friction_velocity", "m/s"}, s.penalty.friction_velocity);
  s.friction = p.nonNegative({"friction", "1"}, s.friction);
  s.margin = p.nonNegative({"margin", "m"}, s.margin);
  s.continuous = p.boolean("continuous", s.continuous);
  s.cell_size = p.nonNegative({"cell_size", "m"}, s.cell_size);
  s.stabilization = p.positive({"stabilization", "1/s"}, 0.0);
  s.friction_rate = p.positive({"friction_rate", "1/s"}, 0.0);
  s.max_penetration = p.nonNegative({"max_penetration", "1"}, s.max_penetration);
  if (s.max_penetration >= 1.0) p.fail("max_penetration", "a fraction of the contact distance in [0, 1)");
  s.max_slide = p.nonNegative({"max_slide", "m"}, 0.0);
  s.contact_halvings = p.integer("contact_halvings", 0, s.contact_halvings);
  if (s.contact_halvings > 5)  // the scene halves a step 6 times at most (a pass-through beyond is a fault)
    p.fail("contact_halvings", "at most 5 (sub-steps of dt / 32)");
  return std::make_unique<ContactPipeline>(s);
}

void ContactPipeline::init(const Scene& scene) {
  models_.clear();
  obstacles_.clear();
  scene.root().collect(models_);
  scene.root().collect(obstacles_);
  for (SphereCollisionModel* m : models_) m->init(scene);
  findTubes();
  // Margin: contacts are kept up to half the smallest radius of gap (beyond the sweep).
  double smallest = std::numeric_limits<double>::infinity();
  for (const SphereCollisionModel* m : models_) smallest = std::min(smallest, m->smallestRadius());
  margin_ = settings_.margin >= 0.0 ? settings_.margin : (std::isfinite(smallest) ? 0.5 * smallest : 0.0);
  broad_phase_ = UniformGridBroadPhase(settings_.cell_size);
  contacts_.clear();
  restored_ = false;  // a new layout: the next detection starts afresh, restored or not
}

void ContactPipeline::findTubes() {
  const int count = static_cast<int>(models_.size());
  tube_of_.assign(count, -1);
  for (int m = 0; m < count; ++m) {
    const SphereCollisionModel& model = *models_[m];
    if (model.inside().empty()) continue;
    const std::string where = model.origin() + "/inside";
    for (int t = 0; t < count; ++t)
      if (t != m && models_[t]->node() && models_[t]->node()->path() == model.inside()) tube_of_[m] = t;
    if (tube_of_[m] < 0) {
      std::string known;
      for (const SphereCollisionModel* t : models_)
        if (t != &model && t->node()) known += (known.empty() ? "" : ", ") + describeJson(t->node()->path());
      throw SceneError(where, "the node path of a body with a SphereCollisionModel (" + (known.empty() ? std::string("there is none") : known) + ")",
                       describeJson(model.inside()));
    }
    const SphereCollisionModel& tube = *models_[tube_of_[m]];
    // The instrument's every section fits the lumen's narrowest (a thick shaft pushed into a
    // narrower lumen would be a contact no position satisfies).
    if (!(tube.narrowestLumen() > model.radius()))
      throw SceneError(where, "a tube whose SphereCollisionModel has a \"lumen_radius\" above this instrument's radius " +
                                  describeJson(model.radius()) + " m" + " all along (\"lumen_spans\" included)",
                       describeJson(model.inside()) + (tube.lumenRadius() > 0.0 ? " with a lumen of radius " + describeJson(tube.narrowestLumen()) + " m at its narrowest"
                                                                                 : std::string(" without a lumen_radius")));
  }
  // One level: an instrument inside a tube that is itself inside another (a wire in a
  // microcatheter in a guide catheter) would also need the outer lumen where it leaves the inner
  // tube, and no ordinary contacts with the outer tube where it is inside both: not built.
  for (int m = 0; m < count; ++m)
    if (tube_of_[m] >= 0 && tube_of_[tube_of_[m]] >= 0)
      throw SceneError(models_[m]->origin() + "/inside",
                       "a tube that does not itself run inside another (one level of coaxial instruments is built)",
                       describeJson(models_[m]->inside()) + ", inside " + describeJson(models_[tube_of_[m]]->inside()));
  place_.assign(count, {});
  for (int m = 0; m < count; ++m)  // room for stretching to twice the length, as the models' own
    if (tube_of_[m] >= 0) place_[m].reserve(2 * static_cast<std::size_t>(models_[m]->sphereCount()));
}

bool ContactPipeline::heldInside(int a, int k, int b, int l) const {
  const auto chordInside = [&](int model, int chord) {
    const std::vector<TubePlace>& place = place_[model];
    return chord + 1 < static_cast<int>(place.size()) &&
           (place[chord] != TubePlace::kOutside || place[chord + 1] != TubePlace::kOutside);
  };
  if (tube_of_[a] == b) return chordInside(a, k);
  if (tube_of_[b] == a) return chordInside(b, l);
  return false;
}

void ContactPipeline::beginStep(const Scene& scene, const SceneState& s, double h) {
  // Baumgarte ω of contact rows: critically damped over two steps of the step about to be taken
  // (ω h = ½: the normal row then keeps g1 >= ¾ g0 over the step, to first order).
  time_step_ = h;
  scene_dt_ = scene.settings().dt;
  stabilization_ = settings_.stabilization > 0.0 ? settings_.stabilization : 0.5 / h;
  friction_rate_ = settings_.friction_rate > 0.0 ? settings_.friction_rate : stabilization_;
  // 1. Spheres on the current curves, centres and velocities mapped down.
  stats_ = Statistics();
  for (SphereCollisionModel* m : models_) {
    m->update(s);
    stats_.spheres += m->sphereCount();
  }
  for (Obstacle* o : obstacles_) o->moveTo(s.time);
  if (!restored_) rememberForces();
  restored_ = false;
  contacts_.clear();

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

  // 2b. Instruments inside tubes: held in the lumen.
  for (int m = 0; m < model_count; ++m) {
    const int t = tube_of_[m];
    if (t < 0) continue;
    const double mu = models_[t]->lumenFriction().value_or(settings_.friction);
    findLumenContacts(*models_[m], m, *models_[t], t, mu, narrow, contacts_, place_[m], axis_bounds_);
  }
  stats_.lumen_contacts = static_cast<int>(contacts_.size()) - stats_.obstacle_contacts;

  // 3. Thread–thread: chords in bounding spheres of their start and predicted end positions.
  chords_.clear();
  chord_owner_.clear();
  const double sweep = narrow.time_step;
  for (int m = 0; m < model_count; ++m) {
    const SphereCollisionModel& model = *models_[m];
    if (model_count == 1 && !model.selfCollision()) continue;
    const Points& x = model.centers();
    const Points& v = model.velocities();
    for (int k = 0; k + 1 < model.sphereCount(); ++k) {
      if (!model.mapping().joinsNext(k)) continue;  // a cut: no chord across it
      const Vec3 a0 = x.row(k).transpose(), a1 = x.row(k + 1).transpose();
      const Vec3 b0 = a0 + sweep * v.row(k).transpose(), b1 = a1 + sweep * v.row(k + 1).transpose();
      chords_.push_back(sweptChordBound(a0, a1, b0, b1, model.chordRadius(k) + 0.5 * margin_));
      chord_owner_.emplace_back(m, k);
    }
  }
  stats_.chords = static_cast<int>(chords_.size());
  if (chords_.size() >= 2) {
    // A contact set cut short by the budget is not used blindly: missedContact halves the step.
    stats_.pairs_overflow = !broad_phase_.findPairs(chords_, pairs_);
    stats_.candidate_pairs = static_cast<int>(pairs_.size());
    for (const IndexPair& pair : pairs_) {
      const auto [ma, k] = chord_owner_[pair.first];
      const auto [mb, l] = chord_owner_[pair.second];
      if (heldInside(ma, k, mb, l)) continue;  // held in the lumen instead (2b)
      if (ma == mb) {
        const SphereCollisionModel& model = *models_[ma];
        if (!model.selfCollision()) continue;
        // Every point of chords k and l is closer than (|k − l| + 1) h along the curve (chords
        // of two strands of a cut thread are not near along it, however close their indices).
        if (model.mapping().chordDistanceBound(k, l) < model.exclusion(k, l)) continue;
      }
      findChordContact(*models_[ma], ma, k, *models_[mb], mb, l, narrow, contacts_);
    }
  }
  stats_.thread_contacts = static_cast<int>(contacts_.size()) - stats_.obstacle_contacts - stats_.lumen_contacts;
  if (settings_.max_slide > 0.0) {
    start_offset_.resize(contacts_.size());
    for (std::size_t i = 0; i < contacts_.size(); ++i) {
      const ContactKinematics k = contactKinematics(contacts_[i], s);
      start_offset_[i] = k.x_a - k.x_b;
    }
  }
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

void ContactPipeline::contactAbscissas(const MechanicalState& body, std::vector<double>& out) const {
  if (body.pointCount() == 0) return;
  for (const Contact& c : contacts_) {
    if (c.a.body() == &body) out.push_back(c.a.abscissa());
    if (c.model_b >= 0 && c.b.body() == &body) out.push_back(c.b.abscissa());
  }
}

int ContactPipeline::addContactRows(const SceneState& s, ConstraintRows& rows) {
  if (settings_.response != Response::kUnilateral) return 0;
  const int first = rows.rows();
  const int count = static_cast<int>(contacts_.size());
  normal_row_.resize(count);
  tangent1_.resize(count);
  tangent2_.resize(count);
  const double w = stabilization_, wf = friction_rate_;
  for (int i = 0; i < count; ++i) {
    const Contact& c = contacts_[i];
    const ContactKinematics k = contactKinematics(c, s);
    rows.beginAnchor();
    c.a.forEachWeight([&](int point, double weight) { rows.addAnchorPoint(point, weight); });
    if (!c.againstObstacle()) c.b.forEachWeight([&](int point, double weight) { rows.addAnchorPoint(point, -weight); });
    // n·(a_A − a_B) >= −2ω ġ − ω² g (the obstacle surface moves at constant velocity over the
    // step); t_j·(a_A − a_B) = −ω_f t_j·(v_A − v_B).
    const auto [t1, t2] = constraints::orthonormalComplement(c.normal);
    const Vec3 v = k.v_a - k.v_b;
    tangent1_[i] = t1;
    tangent2_[i] = t2;
    // Warm start: the force this contact had in the last solve, in the new directions.
    const Vec3 previous = rememberedForce(c);
    const Vec3 guess(previous.dot(c.normal), previous.dot(t1), previous.dot(t2));
    normal_row_[i] = rows.addContactRows(c.normal, -2.0 * w * k.gap_rate - w * w * k.gap, c.friction, t1,
                                         -wf * t1.dot(v), t2, -wf * t2.dot(v), guess) - first;
  }
  return rows.rows() - first;
}

void ContactPipeline::rememberForces() {
  // The contacts of the last solve with their forces, sorted by (model A, model B, obstacle, s_A)
  // for rememberedForce. Only when the forces belong to this contact set (takeMultipliers ran
  // after the detection that made it).
  remembered_.clear();
  if (contact_force_.size() == contacts_.size())
    for (std::size_t i = 0; i < contacts_.size(); ++i) {
      const Contact& c = contacts_[i];
      remembered_.push_back({c.model_a, c.model_b, c.obstacle, c.a.abscissa(), c.b.abscissa(), contact_force_[i]});
    }
  sortRemembered();
  contact_force_.clear();
}

void ContactPipeline::sortRemembered() {
  std::sort(remembered_.begin(), remembered_.end(), [](const RememberedContact& x, const RememberedContact& y) {
    return std::tie(x.model_a, x.model_b, x.obstacle, x.abscissa_a) < std::tie(y.model_a, y.model_b, y.obstacle, y.abscissa_a);
  });
}

void ContactPipeline::saveMemory(StepMemory& memory) const {
  // What rememberForces will keep at the next beginStep, in the same order (so that the sort
  // orders it the same way).
  memory.contacts.clear();
  if (contact_force_.size() != contacts_.size()) return;
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    const Contact& c = contacts_[i];
    const Vec3& f = contact_force_[i];
    memory.contacts.insert(memory.contacts.end(), {double(c.model_a), double(c.model_b), double(c.obstacle), c.a.abscissa(),
                                                   c.b.abscissa(), f.x(), f.y(), f.z()});
  }
}

void ContactPipeline::restoreMemory(const StepMemory& memory) {
  remembered_.clear();
  for (std::size_t k = 0; k + 8 <= memory.contacts.size(); k += 8) {
    const double* m = &memory.contacts[k];
    remembered_.push_back({static_cast<int>(m[0]), static_cast<int>(m[1]), static_cast<int>(m[2]), m[3], m[4],
                           Vec3(m[5], m[6], m[7])});
  }
  sortRemembered();
  // The contacts of the state left behind are not this state's: none until the next detection.
  contacts_.clear();
  contact_force_.clear();
  restored_ = true;
}

Vec3 ContactPipeline::rememberedForce(const Contact& c) const {
  // The same contact in the last solve: same models or obstacle, abscissas within one sphere
  // spacing of A's sampling (a contact slides along the threads by less than that per step);
  // the closest such one.
  const SphereCollisionModel& a = *models_[c.model_a];
  const double reach = 1.0 / std::max(1, a.sphereCount() - 1);
  const RememberedContact low{c.model_a, c.model_b, c.obstacle, c.a.abscissa() - reach, 0.0, Vec3::Zero()};
  auto it = std::lower_bound(remembered_.begin(), remembered_.end(), low, [](const RememberedContact& x, const RememberedContact& y) {
    return std::tie(x.model_a, x.model_b, x.obstacle, x.abscissa_a) < std::tie(y.model_a, y.model_b, y.obstacle, y.abscissa_a);
  });
  Vec3 force = Vec3::Zero();
  double closest = 2.0 * reach;
  for (; it != remembered_.end() && it->model_a == c.model_a && it->model_b == c.model_b && it->obstacle == c.obstacle &&
         it->abscissa_a <= c.a.abscissa() + reach;
       ++it) {
    const double distance = std::abs(it->abscissa_a - c.a.abscissa()) + (c.againstObstacle() ? 0.0 : std::abs(it->abscissa_b - c.b.abscissa()));
    if (distance < closest) {
      closest = distance;
      force = it->force;
    }
  }
  return force;
}

void ContactPipeline::takeMultipliers(Eigen::Ref<const VecX> lambda, int first) {
  // Force on thread point A: λ_n n + λ_t1 t1 + λ_t2 t2.
  const int count = static_cast<int>(contacts_.size());
  contact_force_.resize(count);
  for (int i = 0; i < count; ++i) {
    const int r = first + normal_row_[i];
    contact_force_[i] = lambda[r] * contacts_[i].normal;
    if (contacts_[i].friction > 0.0) contact_force_[i] += lambda[r + 1] * tangent1_[i] + lambda[r + 2] * tangent2_[i];
  }
}

Vec3 ContactPipeline::contactForce(int i, const SceneState& s) const {
  if (settings_.response == Response::kUnilateral)
    return i < static_cast<int>(contact_force_.size()) ? contact_force_[i] : Vec3::Zero();
  const Contact& c = contacts_[i];
  return penaltyForce(c, contactKinematics(c, s), settings_.penalty).force;
}

CollisionPipeline::Miss ContactPipeline::missedContact(const SceneState& after) {
  // The start's contact set is incomplete, whatever the response: the step was too large.
  if (stats_.pairs_overflow) return Miss::kTooFar;
  if (settings_.response != Response::kUnilateral) return Miss::kNone;
  // Depth and slide tests while the sub-step may still be halved (contact_halvings).
  const bool may_halve = time_step_ > 1.5 * scene_dt_ / static_cast<double>(1 << settings_.contact_halvings);
  const bool depth_test = settings_.max_penetration > 0.0 && may_halve;
  if (settings_.max_slide > 0.0 && may_halve && start_offset_.size() == contacts_.size() &&
      contact_force_.size() == contacts_.size())
    for (std::size_t i = 0; i < contacts_.size(); ++i) {
      const Contact& c = contacts_[i];
      if (c.againstObstacle() || contact_force_[i].dot(c.normal) <= 0.0) continue;  // pressed thread contacts
      // Along a lumen, sliding is the instrument's motion: its rows are the lumen's, and a sphere
      // that slides around the wall or through a bend out of them is caught by leftLumen.
      if (c.insideLumen()) continue;
      const ContactKinematics k = contactKinematics(c, after);
      const Vec3 moved = (k.x_a - k.x_b) - start_offset_[i];
      if ((moved - moved.dot(c.normal) * c.normal).norm() > settings_.max_slide) return Miss::kOverlapOrSlide;
    }
  const double keep = 1.0 - settings_.max_penetration;  // centre lines kept (1 − p) R apart
  const int model_count = static_cast<int>(models_.size());
  if (static_cast<int>(after_centers_.size()) != model_count) after_centers_.resize(model_count);
  // (The chords in beginStep's order: the same models, skipped and cut alike.)
  end_chords_.clear();
  for (int m = 0; m < model_count; ++m) {
    const SphereCollisionModel& model = *models_[m];
    if (model_count == 1 && !model.selfCollision()) continue;
    Points& end = after_centers_[m];
    if (end.rows() != model.sphereCount()) end.resize(model.sphereCount(), 3);
    model.mapping().apply(model.curve().block(after.q), end);
    const Points& start = model.centers();
    for (int k = 0; k + 1 < model.sphereCount(); ++k) {
      if (!model.mapping().joinsNext(k)) continue;  // a cut: no chord across it
      const Vec3 a0 = start.row(k).transpose(), a1 = start.row(k + 1).transpose();
      const Vec3 b0 = end.row(k).transpose(), b1 = end.row(k + 1).transpose();
      end_chords_.push_back(sweptChordBound(a0, a1, b0, b1, depth_test ? keep * model.chordRadius(k) : 0.0));  // centre lines
    }
  }
  if (depth_test && leftLumen()) return Miss::kOverlapOrSlide;
  if (end_chords_.size() < 2) return Miss::kNone;
  if (!findEndPairs()) return Miss::kTooFar;
  Miss miss = Miss::kNone;
  for (const IndexPair& pair : end_pairs_) {
    const auto [ma, k] = chord_owner_[pair.first];
    const auto [mb, l] = chord_owner_[pair.second];
    const SphereCollisionModel& a = *models_[ma];
    const SphereCollisionModel& b = *models_[mb];
    if (heldInside(ma, k, mb, l)) continue;  // one runs inside the other: their centre lines are meant to be close
    // As in beginStep: a body without self-collision may pass through itself; neighbouring chords
    // share a sphere (their centre lines always meet there), and nearer ones than the exclusion.
    if (ma == mb && (!a.selfCollision() ||
                     (a.mapping().strandOf(k) == a.mapping().strandOf(l) && std::abs(k - l) <= 1) ||
                     a.mapping().chordDistanceBound(k, l) < a.exclusion(k, l)))
      continue;
    MovingSegment sa{a.centers().row(k).transpose(), a.centers().row(k + 1).transpose(),
                     after_centers_[ma].row(k).transpose(), after_centers_[ma].row(k + 1).transpose()};
    MovingSegment sb{b.centers().row(l).transpose(), b.centers().row(l + 1).transpose(),
                     after_centers_[mb].row(l).transpose(), after_centers_[mb].row(l + 1).transpose()};
    // Centre lines meet: closer than a thousandth of the radius at a coplanarity root (strands in
    // contact stay two radii apart; only a pass-through brings the lines together).
    if (firstSegmentContact(sa, sb, 1e-3 * std::min(a.smallestRadius(), b.smallestRadius()))) return Miss::kPassThrough;
    // Overlap: the step brought the centre lines closer than (1 − p) R and closer than at its
    // start. The step's contacts hold their pairs to within Baumgarte's correction of R = r_a +
    // r_b; a pair this deep was not among them (it came into contact within the step, e.g. two
    // threads closing like scissors along their length) or slid out of its rows' normals.
    if (!depth_test || miss != Miss::kNone) continue;
    const SegmentClosestPoints end_points = closestPointsOnSegments(sa.end0, sa.end1, sb.end0, sb.end1);
    const double end = end_points.distance;
    if (end < keep * (a.chordRadius(k, end_points.s) + b.chordRadius(l, end_points.t)) &&
        end < closestPointsOnSegments(sa.start0, sa.start1, sb.start0, sb.start1).distance)
      miss = Miss::kOverlapOrSlide;
  }
  return miss;
}

bool ContactPipeline::findEndPairs() {
  // Sphere B ⊂ sphere A when |c_B − c_A| + ρ_B <= ρ_A. If every chord's end bound lies in its
  // start bound, two end bounds that overlap have start bounds that overlap (|c_A,i − c_A,j| <=
  // |c_B,i − c_B,j| + (ρ_A,i − ρ_B,i) + (ρ_A,j − ρ_B,j) <= ρ_A,i + ρ_A,j), so beginStep's pairs hold
  // every candidate: the usual case, as a step ends near where its start's velocities predicted
  // and the start bounds are padded by r + margin/2 against the end's (1 − p) r. The slack of
  // 1e-9 ρ_A covers the round-off of the broad phase's squared-distance test.
  assert(chord_owner_.size() == end_chords_.size() && "missedContact's chords are beginStep's");
  bool inside = chords_.size() == end_chords_.size();
  for (std::size_t i = 0; inside && i < end_chords_.size(); ++i) {
    const BoundingSphere &start = chords_[i], &end = end_chords_[i];
    inside = (end.center - start.center).norm() + end.radius <= (1.0 - 1e-9) * start.radius;
  }
  if (!inside) return broad_phase_.findPairs(end_chords_, end_pairs_);
  // beginStep's pairs whose end bounds overlap: the broad phase's answer, in its sorted order.
  end_pairs_.clear();  // (capacity kept: grows only)
  for (const IndexPair& pair : pairs_) {
    const BoundingSphere &u = end_chords_[pair.first], &w = end_chords_[pair.second];
    const double reach = u.radius + w.radius;
    if ((u.center - w.center).squaredNorm() <= reach * reach) end_pairs_.push_back(pair);
  }
  return true;
}

bool ContactPipeline::leftLumen() const {
  // A sphere of an instrument held inside its tube at the step's start that ended the step
  // beyond the lumen's wall by more than p times the clearance R_in − r (p = "max_penetration"),
  // and further out than it began: the rows of the step's start did not follow it (it came to
  // the wall within the step, or crossed the lumen). The clearance, not the radius, is the
  // scale: a wire's clearance in its catheter is a fifth of its radius or less.
  for (int m = 0; m < static_cast<int>(models_.size()); ++m) {
    const int t = tube_of_[m];
    if (t < 0) continue;
    const SphereCollisionModel& inner = *models_[m];
    const SphereCollisionModel& tube = *models_[t];
    const double overshoot = 1.0 + settings_.max_penetration;
    const std::vector<TubePlace>& place = place_[m];
    axis_bounds_.build(after_centers_[t], tube.sphereCount());
    start_axis_bounds_.build(tube.centers(), tube.sphereCount());
    int hint = -1;  // the last sphere's chord at the step's end: its neighbour's is near
    for (int k = 0; k < inner.sphereCount() && k < static_cast<int>(place.size()); ++k) {
      if (place[k] != TubePlace::kInside) continue;  // not held by the lumen
      const AxisPoint end = nearestAxisPoint(after_centers_[t], tube.mapping(), after_centers_[m].row(k).transpose(),
                                             &axis_bounds_, hint);
      if (end.chord >= 0) hint = end.chord;
      if (end.chord < 0 || end.distance <= overshoot * (tube.lumenRadius(end.chord, end.u) - inner.radius(k)))
        continue;  // (R_in − r_k) the clearance
      const AxisPoint start = nearestAxisPoint(tube.centers(), tube.mapping(), inner.centers().row(k).transpose(),
                                               &start_axis_bounds_, end.chord);
      if (end.distance > start.distance) return true;
    }
  }
  return false;
}

Vec3 ContactPipeline::obstacleForce(int o, const SceneState& s) const {
  // Action and reaction: the obstacle receives −F of every contact it takes part in.
  Vec3 sum = Vec3::Zero();
  for (int i = 0; i < static_cast<int>(contacts_.size()); ++i)
    if (contacts_[i].obstacle == o) sum -= contactForce(i, s);
  return sum;
}

}  // namespace filum::collision
