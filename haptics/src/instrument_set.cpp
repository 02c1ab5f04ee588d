#include "filum/haptics/instrument_set.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "filum/collision/contact_pipeline.hpp"
#include "filum/collision/segment_closest_points.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/haptics/event_number.hpp"
#include "filum/geometry/arc_length.hpp"

namespace filum::haptics {

namespace {

/// The strand of the curve holding abscissa s (the first one whose end is past s).
Strand strandAt(const CurveBasis& basis, double s) {
  const std::vector<Strand> all = strands(basis);
  for (const Strand& strand : all)
    if (s < strand.end) return strand;
  return all.back();
}

/// The curve body of the node whose path p[key] names; refused at p[key] otherwise.
const CurveBody* curveAt(const Scene& scene, const Params& p, const std::string& key) {
  const std::string path = p.string(key);
  const MechanicalState* body = scene.bodyAt(path);
  if (!body || !body->curve()) p.fail(key, "the path of a node holding a curve body (e.g. \"tube\")", "\"" + path + "\"");
  return body->curve();
}

/// The curve body of the scene that `body` is, for a layout change (Scene::cut needs it mutable).
CurveBody* mutableCurve(Scene& scene, const CurveBody* body) {
  for (MechanicalState* state : scene.bodies())
    if (state->curve() == body) return state->curve();
  return nullptr;
}

}  // namespace

std::unique_ptr<InstrumentSet> InstrumentSet::fromScene(const nlohmann::json& document, const std::string& source,
                                                        Scene& scene, double duration) {
  if (!document.is_object() || !document.contains("instruments")) return nullptr;
  const Params top(document, source, "");
  std::unique_ptr<InstrumentSet> set(new InstrumentSet());
  if (top.has("metrics")) {
    const Params m = top.object("metrics").withOwner("metrics");
    set->metrics_ = TraineeMetrics(m.positive({"idle_speed", "m/s"}, 5e-3));
    if (m.has("specimen")) {
      const Params sp = m.object("specimen");
      set->specimen_ = curveAt(scene, sp, "body");
      set->specimen_kept_end_ = sp.number({"kept_end", "1"}, 0.0);
      if (set->specimen_kept_end_ != 0.0 && set->specimen_kept_end_ != 1.0)
        sp.fail("kept_end", "0 or 1: the end of the body that stays in the patient", describeJson(sp.raw({"kept_end", "1"})));
      sp.finish();
      set->metrics_.setRemovedLength(0.0);
    }
    if (m.has("inspection")) {
      const Params in = m.object("inspection");
      set->inspected_ = curveAt(scene, in, "body");
      set->inspection_step_ = in.positive({"max_step", "m"}, 0.1);
      in.finish();
      set->metrics_.setInspected(0.0, 0.0);
    }
    m.finish();
  }
  if (top.has("needles")) {
    for (const Params& item : top.objects("needles")) {
      const Params p = item.withOwner("needles");
      Needle::Settings settings = Needle::settingsFromParams(p);
      for (const auto& other : set->needles_)
        if (other->name() == settings.name) p.fail("name", "a name no other needle has", "\"" + settings.name + "\" again");
      if (!settings.thread.empty()) {
        const MechanicalState* body = scene.bodyAt(settings.thread);
        if (!body || !body->curve()) p.fail("thread", "the path of a node holding a curve body (e.g. \"suture\")");
      }
      set->needles_.push_back(std::make_unique<Needle>(std::move(settings)));
    }
  }
  if (top.has("wound"))
    set->wound_ = std::make_unique<Wound>(Wound::settingsFromParams(top.object("wound").withOwner("wound"), scene));
  const std::vector<Params> items = top.objects("instruments");
  if (items.empty()) top.fail("instruments", "a list of at least one instrument ({\"name\", \"type\", \"path\"})");
  for (const Params& item : items) {
    const Params p = item.withOwner("instruments");
    InstrumentSettings settings = InstrumentSettings::fromParams(p);
    for (const auto& other : set->instruments_)
      if (other->name() == settings.name) p.fail("name", "a name no other instrument has", "\"" + settings.name + "\" again");
    if (settings.collide && !scene.collisionPipeline())
      p.fail("collide",
             "false, or a collision pipeline in the scene (\"collision\": {\"type\": \"ContactPipeline\"} and "
             "collision models on the threads) for the instrument's shaft and jaws to touch them",
             "true");
    for (const std::string& path : settings.coagulation_objects) {
      const MechanicalState* named = scene.bodyAt(path);
      if (!named || !named->curve())
        p.fail("require_coagulation", "paths of nodes holding curve bodies (e.g. \"tube\")", "\"" + path + "\"");
    }
    set->metrics_.addInstrument(settings.name, instrumentKindName(settings.kind));
    const bool device = settings.device;
    set->instruments_.push_back(std::make_unique<Instrument>(std::move(settings)));
    set->devices_.emplace_back();
    if (device) {
      // A "haptics" block without "tool", and the instrument's own fields.
      const Params d = p.object("device").withOwner("instruments");
      Instrument& inst = *set->instruments_.back();
      set->devices_.back() = HapticSession::forInstrument(d, inst.hold(), duration);
      const Vec3 direction = d.vec3({"direction", "1"}, Vec3(0, 0, -1));
      if (!(direction.norm() > 0.0)) d.fail("direction", "a non-zero vector (the shaft's axis towards the tip)");
      const unsigned button = 1u << (d.integer("button", 1, 16, 1, "a button of the stylus, 1 to 16") - 1);
      inst.driveByDevice(instrumentFrame(direction, d.number({"roll", "rad"}, 0.0)), button, d.positive({"jaw_speed", "1/s"}, 5.0));
      d.finish();
    }
  }
  set->attach(scene, source);
  return set;
}

void InstrumentSet::attach(Scene& scene, const std::string& source) {
  dt_ = scene.settings().dt;
  const int count = size();
  fields_.assign(count, {});
  released_.assign(count, {});
  coagulating_done_.assign(count, 0);
  held_strands_.assign(count, {});
  touching_.assign(count * count, 0);
  for (int i = 0; i < count; ++i) {
    Instrument& inst = *instruments_[i];
    const std::string origin = source + ": /instruments/" + std::to_string(i);
    if (inst.settings().collide) {
      for (int k = 0; k < Instrument::kParts; ++k) {
        auto part = inst.makePart(k);
        part->setOrigin(origin);
        scene.root().addComponent(std::move(part));
      }
    }
    for (MechanicalState* body : scene.bodies()) {
      if (!body->curve()) continue;
      auto field = std::make_unique<ToolForceField>(inst.hold());
      field->setName(inst.name() + " hold");
      field->setOrigin(origin + " (on " + body->describe() + ")");
      fields_[i].push_back(field.get());
      body->node()->addComponent(std::move(field));
    }
    if (devices_[i]) devices_[i]->setFields({fields_[i].begin(), fields_[i].end()});
  }
  // The swage's hold on each needle's thread, on that thread's body only.
  for (std::size_t k = 0; k < needles_.size(); ++k) {
    const Needle& needle = *needles_[k];
    if (needle.settings().thread.empty()) continue;
    MechanicalState* body = scene.bodyAt(needle.settings().thread);
    for (const auto& hold : {needle.swageHold(), needle.swageLeadHold()}) {
      auto field = std::make_unique<ToolForceField>(hold);
      field->setName(needle.name() + (hold == needle.swageHold() ? " swage" : " swage lead"));
      field->setOrigin(source + ": /needles/" + std::to_string(k) + " (on " + body->describe() + ")");
      body->node()->addComponent(std::move(field));
    }
  }
  if (wound_) wound_->attach(scene, source + ": /wound");
  scene.init();
  if (wound_) wound_->bind(scene, needles_);
  if (inspected_) {
    // The body's length from s = 0 as it lies at the start, at 1001 abscissas (arc length,
    // geometry/arc_length.hpp; GraspCoverage interpolates linearly between them).
    const geometry::ArcLengthParameterization arc(inspected_->basis(), inspected_->block(scene.state().q));
    std::vector<double> length_at(1001);
    for (int k = 0; k <= 1000; ++k) length_at[k] = arc.lengthAt(k / 1000.0);
    coverage_ = std::make_unique<GraspCoverage>(std::move(length_at), inspection_step_);
  }
  for (auto& needle : needles_) {
    if (needle->settings().thread.empty()) continue;
    const CurveBody& thread = *scene.bodyAt(needle->settings().thread)->curve();
    const double end = needle->settings().abscissa;
    grasp(*needle->swageHold(), thread, end);
    // The lead hold kSwageLead along the thread from the swaged end (its arc length at the start).
    const geometry::ArcLengthParameterization arc(thread.basis(), thread.block(scene.state().q));
    const double lead = Needle::kSwageLead / arc.lengthAt(1.0);
    grasp(*needle->swageLeadHold(), thread, std::clamp(end < 0.5 ? end + lead : end - lead, 0.0, 1.0));
    needle->move(needle->pose(), needle->pose(), scene.state().time, dt_);
  }
  // Parts where they are at the start (drawn before the first step; the first beforeStep moves
  // them): a device's stylus where its first tick has it (lockstep; a threaded servo has not
  // started yet, and its instrument waits at the origin until it has).
  for (int i = 0; i < count; ++i) {
    ServoSample sample;
    if (devices_[i] && devices_[i]->stylus(scene, sample))
      instruments_[i]->setStylus(sample.position, sample.velocity, sample.time, sample.buttons);
    instruments_[i]->setTime(scene.state().time, dt_);
    // The metrics start from where the instrument is at the start.
    const double t = scene.state().time;
    metrics_.start(i, instruments_[i]->settings().shape.tip(instruments_[i]->poseAt(t), instruments_[i]->jawAt(t)),
                   instruments_[i]->jawAt(t));
  }
}

void InstrumentSet::event(double t, const std::string& what) {
  events_.push_back("t = " + eventNumber(t) + " s: " + what);
}

void InstrumentSet::beforeStep(Scene& scene) {
  const double t = scene.state().time;
  // Every instrument, and the needles they hold, to the step's start; then the jaws' events.
  for (int i = 0; i < size(); ++i) {
    ServoSample sample;
    if (devices_[i] && devices_[i]->stylus(scene, sample))
      instruments_[i]->setStylus(sample.position, sample.velocity, sample.time, sample.buttons);
    instruments_[i]->setTime(t, dt_);
  }
  moveNeedles(t);
  for (int i = 0; i < size(); ++i) {
    Instrument& inst = *instruments_[i];
    if (inst.letsGo() && inst.holdsObject()) {
      for (auto& needle : needles_)
        if (needle->holder == i) {
          needle->holder = -1;
          event(t, "'" + inst.name() + "' let go of '" + needle->name() + "'");
        }
      inst.releaseObject();
    } else if (inst.letsGo()) {
      released_[i].push_back(inst.hold()->grasp.body());
      event(t, "'" + inst.name() + "' let go at s = " + eventNumber(inst.hold()->grasp.abscissa()));
      inst.stopHolding();
    }
    if (!inst.holding() && !inst.holdsObject() && inst.closing() && !inst.latched()) closeJaws(i, scene);
    if (inst.reachedClosed() && !inst.holding() && !inst.holdsObject() && !inst.latched()) {
      inst.latch();  // this closing missed: it catches nothing more until the jaws open again
      if (inst.kind() != InstrumentKind::kScissors) ++metrics_.instrument(i).missed_grasps;
      event(t, "'" + inst.name() + "' closed on nothing");
    }
  }
  moveNeedles(t);
  setHeldSpans(scene);
  if (wound_)
    for (const std::string& what : wound_->follow(scene, needles_)) event(t, what);
}

bool InstrumentSet::catchNeedle(int i, double t) {
  Instrument& inst = *instruments_[i];
  const InstrumentShape& shape = inst.settings().shape;
  // The wire point nearest to the jaws' midline that was between them and that they closed onto,
  // over 64 samples of each needle's arc (a 135° arc of 8 mm: one sample per 0.3 mm).
  Needle* best = nullptr;
  double nearest = 0.0;
  for (auto& needle : needles_) {
    const double r = needle->settings().wire_radius;
    for (int k = 0; k < 64; ++k) {
      const Vec3 x = needle->point(needle->pose(), needle->settings().arc * k / 63.0);
      const double d = betweenJaws(shape, inst.pose(), inst.previousOpening(), x, r);
      if (d < 0.0 || !jawsClosedOn(shape, inst.opening(), jawCoordinates(inst.pose(), x).along, r)) continue;
      if (!best || d < nearest) {
        best = needle.get();
        nearest = d;
      }
    }
  }
  if (!best) return false;
  InstrumentTally& tally = metrics_.instrument(i);
  ++tally.grasps;
  if (best->ever_held) ++tally.regrasps;
  if (best->holder >= 0 && best->holder != i) {
    instruments_[best->holder]->releaseObject();
    event(t, "'" + inst.name() + "' took '" + best->name() + "' from '" + instruments_[best->holder]->name() + "'");
  } else {
    event(t, "'" + inst.name() + "' took '" + best->name() + "'");
  }
  best->holder = i;
  best->ever_held = true;
  best->in_jaws = jawsPose(inst.pose()).inverse() * best->pose();
  inst.holdObject();
  return true;
}

void InstrumentSet::moveNeedles(double t) {
  for (auto& needle : needles_) {
    if (needle->holder < 0) {
      needle->move(needle->pose(), needle->pose(), t, dt_);
      continue;
    }
    const Instrument& inst = *instruments_[needle->holder];
    needle->move(jawsPose(inst.pose()) * needle->in_jaws, jawsPose(inst.poseAt(t + dt_)) * needle->in_jaws, t, dt_);
  }
}

void InstrumentSet::closeJaws(int i, Scene& scene) {
  Instrument& inst = *instruments_[i];
  if (inst.kind() == InstrumentKind::kNeedleHolder && catchNeedle(i, scene.state().time)) {
    inst.latch();
    return;
  }
  const std::optional<JawCatch> c =
      catchBetweenJaws(scene, inst.settings().shape, inst.pose(), inst.previousOpening(), inst.opening());
  if (!c) return;
  inst.latch();
  if (inst.kind() == InstrumentKind::kScissors) {
    cut(i, scene, *c);
    return;
  }
  InstrumentTally& tally = metrics_.instrument(i);
  ++tally.grasps;
  const auto& released = released_[i];
  if (std::find(released.begin(), released.end(), c->body) != released.end()) ++tally.regrasps;
  coagulating_done_[i] = 0;
  inst.startHolding(*c->body, c->abscissa, c->along);
  if (coverage_ && c->body == inspected_ && inst.kind() == InstrumentKind::kGrasper) {
    coverage_->grasp(c->abscissa);
    metrics_.setInspected(coverage_->coveredLength(), coverage_->fraction());
  }
  event(scene.state().time, "'" + inst.name() + "' " +
                                (inst.kind() == InstrumentKind::kBipolarForceps ? "clamped" : "grasped") + " at s = " +
                                eventNumber(c->abscissa));
}

void InstrumentSet::cut(int i, Scene& scene, const JawCatch& c) {
  const Instrument& inst = *instruments_[i];
  InstrumentTally& tally = metrics_.instrument(i);
  const double t = scene.state().time;
  const bool coagulated_here = coagulated(*c.body, c.abscissa);
  bool required = inst.settings().require_coagulation;
  if (required && !inst.settings().coagulation_objects.empty()) {
    required = false;
    for (const std::string& path : inst.settings().coagulation_objects) {
      const MechanicalState* named = scene.bodyAt(path);
      required = required || (named && named->curve() == c.body);
    }
  }
  if (required && !coagulated_here) {
    ++tally.cuts_refused;
    event(t, "'" + inst.name() + "' refused to cut at s = " + eventNumber(c.abscissa) + ": the span is not coagulated");
    return;
  }
  CurveBody* body = mutableCurve(scene, c.body);
  try {
    scene.cut(*body, c.abscissa);
  } catch (const SceneError& e) {
    ++tally.cuts_refused;
    event(t, "'" + inst.name() + "' could not cut at s = " + eventNumber(c.abscissa) + ": " + e.what());
    return;
  }
  ++tally.cuts;
  if (coagulated_here) ++tally.cuts_coagulated;
  event(t, "'" + inst.name() + "' cut at s = " + eventNumber(c.abscissa) + (coagulated_here ? " (coagulated)" : ""));
}

Vec3 InstrumentSet::holdForce(int i, const Scene& scene) const {
  const Instrument& inst = *instruments_[i];
  if (!inst.holding()) return Vec3::Zero();
  for (const ToolForceField* field : fields_[i]) {
    if (field->body().curve() != inst.hold()->grasp.body()) continue;
    const SceneState& s = scene.state();
    const BodyPoint& point = inst.hold()->grasp;
    // The coupling of haptics/tool.hpp: F = k (X(t) − P(s*)) + c (Ẋ − Ṗ(s*)).
    return field->graspStiffness() * (toolPosition(*inst.hold(), s.time) - point.map(s.q)) +
           field->graspDamping() * (inst.hold()->velocity - point.map(s.v));
  }
  return Vec3::Zero();
}

void InstrumentSet::slip(int i, const Scene& scene, const Vec3& force) {
  Instrument& inst = *instruments_[i];
  const BodyPoint& point = inst.hold()->grasp;
  const Vec3 tangent = point.mapTangent(scene.state().q);  // P'(s*), m per unit of s
  const double speed = tangent.norm();
  if (!(speed > 0.0)) return;
  const double pull = force.dot(tangent) / speed;  // F · t̂
  const double excess = std::abs(pull) - inst.settings().holding_force;
  if (excess <= 0.0) return;
  double k = 0.0;
  for (const ToolForceField* field : fields_[i])
    if (field->body().curve() == point.body()) k = field->graspStiffness();
  // The jaws move along the thread by the stretch of the coupling beyond what F_hold bears.
  const double ds = std::copysign(excess / (k * speed), pull);
  const double s = point.abscissa() + ds;
  metrics_.instrument(i).slip_length += std::abs(ds) * speed;
  const double t = scene.state().time;
  // Pulled past the end of its strand (the thread's end, or a cut's), the thread leaves the jaws.
  const Strand strand = heldStrand(i, scene, point.body(), point.abscissa());
  if (s <= strand.begin || s >= strand.end) {
    released_[i].push_back(point.body());
    event(t, "thread pulled out of '" + inst.name() + "'");
    inst.stopHolding();
    return;
  }
  inst.hold()->grasp.moveTo(s);
}

void InstrumentSet::coagulate(int i, const Scene& scene) {
  Instrument& inst = *instruments_[i];
  inst.addHeldTime(dt_);
  if (coagulating_done_[i] || inst.heldFor() < inst.settings().coagulation_time) return;
  coagulating_done_[i] = 1;
  const BodyPoint& point = inst.hold()->grasp;
  // The span under the jaws: half a jaw's length either side, in abscissa through |P'(s*)|, within
  // the strand it is on.
  const double speed = point.mapTangent(scene.state().q).norm();
  if (!(speed > 0.0)) return;
  const double half = 0.5 * inst.settings().shape.jaw_length / speed;
  const Strand strand = strandAt(point.body()->basis(), point.abscissa());
  const double from = std::max(strand.begin, point.abscissa() - half), to = std::min(strand.end, point.abscissa() + half);
  coagulated_.push_back({point.body(), from, to});
  ++metrics_.instrument(i).coagulations;
  event(scene.state().time, "'" + inst.name() + "' coagulated s in [" + eventNumber(from) + ", " + eventNumber(to) + "]");
}

void InstrumentSet::setHeldSpans(const Scene& scene) {
  for (int i = 0; i < size(); ++i) {
    Instrument& inst = *instruments_[i];
    if (!inst.holding()) continue;
    const BodyPoint& point = inst.hold()->grasp;
    const double s = point.abscissa();
    const Strand& strand = heldStrand(i, scene, point.body(), s);
    // The thread between the jaws: along them, within a jaw's length of the held point, plus
    // the jaw's radius and the thread's where it leaves them; across them, within
    // √(2 R r + r²) < R + r of it (a jaw of radius R pressed onto a thread of radius r) — so
    // the held point ± (jaw length + R + r) along the thread, in abscissa through |P'(s*)|.
    const InstrumentShape& shape = inst.settings().shape;
    const double speed = point.mapTangent(scene.state().q).norm();
    // r: the thread's section where it leaves the jaws (a rod's spans), about a jaw's length and
    // radius either side of the held point, or at it where that is larger.
    const CurveBody& body = *point.body();
    const double exit = speed > 0.0 ? (shape.jaw_length + shape.jaw_radius) / speed : 0.0;
    const double r = std::max({body.radiusAt(s), body.radiusAt(std::max(strand.begin, s - exit)),
                               body.radiusAt(std::min(strand.end, s + exit))});
    const double reach = shape.jaw_length + shape.jaw_radius + r;
    const double half = speed > 0.0 ? reach / speed : strand.end - strand.begin;
    inst.setHeldSpan(std::max(strand.begin, s - half), std::min(strand.end, s + half));
  }
}

const Strand& InstrumentSet::heldStrand(int i, const Scene& scene, const CurveBody* body, double s) {
  HeldStrand& held = held_strands_[i];
  // Stale as strandAt would answer otherwise: its strands are half-open, [begin, end), but for
  // the last one, which holds the curve's end (s = 1).
  const bool outside = s < held.strand.begin || s > held.strand.end || (s == held.strand.end && held.strand.end < 1.0);
  if (held.body != body || held.revision != scene.layoutRevision() || outside) {
    held.body = body;
    held.revision = scene.layoutRevision();
    held.strand = strandAt(body->basis(), s);
  }
  return held.strand;
}

bool InstrumentSet::coagulated(const CurveBody& body, double s) const {
  for (const Span& span : coagulated_)
    if (span.body == &body && s >= span.from && s <= span.to) return true;
  return false;
}

Vec3 InstrumentSet::contactOnParts(int i, const Scene& scene) const {
  const auto* pipeline = dynamic_cast<const collision::ContactPipeline*>(scene.collisionPipeline());
  const Instrument& inst = *instruments_[i];
  if (!pipeline || !inst.part(0)) return Vec3::Zero();
  const auto& obstacles = pipeline->obstacles();
  Vec3 sum = Vec3::Zero();
  for (int o = 0; o < static_cast<int>(obstacles.size()); ++o)
    for (int k = 0; k < Instrument::kParts; ++k)
      if (obstacles[o] == inst.part(k)) sum += pipeline->obstacleForce(o, scene.state());
  return sum;
}

double InstrumentSet::partsForce(int i, const Scene& scene) const {
  return contactOnParts(i, scene).norm();  // on the tissue: the same magnitude
}

void InstrumentSet::countToolContacts(double t) {
  const int count = size();
  for (int i = 0; i < count; ++i) {
    for (int j = i + 1; j < count; ++j) {
      // In contact when two parts overlap; apart again only beyond 10 % more than their radii (a
      // graze at the limit counts once, not at every step it flickers across it).
      char& was = touching_[i * count + j];
      const double reach = was ? 1.1 : 1.0;
      bool touching = false;
      for (int a = 0; a < Instrument::kParts && !touching; ++a) {
        for (int b = 0; b < Instrument::kParts && !touching; ++b) {
          const Capsule p = instruments_[i]->partNow(a), q = instruments_[j]->partNow(b);
          touching = collision::closestPointsOnSegments(p.a, p.b, q.a, q.b).distance < reach * (p.radius + q.radius);
        }
      }
      if (touching && !was) {
        metrics_.countToolContact();
        event(t, "'" + instruments_[i]->name() + "' touched '" + instruments_[j]->name() + "'");
      }
      was = touching;
    }
  }
}

void InstrumentSet::afterStep(const Scene& scene) {
  const double t = scene.state().time;
  if (csv_.is_open()) csv_ << t;
  for (int i = 0; i < size(); ++i) {
    Instrument& inst = *instruments_[i];
    const Vec3 hold = holdForce(i, scene);
    if (inst.holding()) {
      if (inst.kind() == InstrumentKind::kGrasper || inst.kind() == InstrumentKind::kNeedleHolder) slip(i, scene, hold);
      if (inst.kind() == InstrumentKind::kBipolarForceps) coagulate(i, scene);
    }
    if (devices_[i]) {
      // The hand feels the hold and the contacts on the parts, around where the step assumed the
      // stylus at its end (the servo's K (x − x0) adds what the hand did beyond that).
      const Vec3 hand = inst.poseAt(t).hinge;
      const bool mirrored = inst.settings().trocar.has_value();
      const Vec3 stylus = mirrored ? Vec3(2.0 * *inst.settings().trocar - hand) : hand;
      const Vec3 velocity = (inst.poseAt(t + dt_).hinge - hand) / dt_ * (mirrored ? -1.0 : 1.0);
      devices_[i]->publishInstrument(scene, contactOnParts(i, scene), stylus, velocity, mirrored);
    }
    const double force = hold.norm() + partsForce(i, scene);
    const double jaw = inst.jawAt(t);
    const Vec3 tip = inst.settings().shape.tip(inst.poseAt(t), jaw);
    const Vec3 before = metrics_.instrument(i).sampled ? metrics_.instrument(i).last : tip;
    metrics_.sample(i, dt_, tip, jaw, force, inst.settings().force_limit);
    if (csv_.is_open())
      csv_ << ',' << tip.x() << ',' << tip.y() << ',' << tip.z() << ',' << jaw << ','
           << (tip - before).norm() / dt_ << ',' << force << ',' << (inst.holding() ? 1 : 0);
  }
  if (wound_) {
    for (const std::string& what : wound_->afterStep(scene.state())) event(t, what);
    if (csv_.is_open())
      csv_ << ',' << wound_->gap(scene.state()) << ',' << wound_->holdingHoles() << ',' << wound_->pressingForce();
  }
  if (csv_.is_open()) csv_ << '\n';
  countToolContacts(t);
  if (specimen_) measureSpecimen(scene);
  metrics_.endStep(t, dt_);
  for (; ruptures_seen_ < scene.ruptures().size(); ++ruptures_seen_) {
    const Scene::Rupture& r = scene.ruptures()[ruptures_seen_];
    metrics_.countBreak();
    event(r.time, r.body + " broke at s = " + eventNumber(r.abscissa) + " under " + eventNumber(r.tension) + " N");
  }
}

InstrumentSet::~InstrumentSet() { finish(); }

bool InstrumentSet::takeOver(int i, double t) {
  Instrument& inst = *instruments_[i];
  if (devices_[i]) return false;
  if (!inst.drivenByDevice()) {
    const InstrumentPose pose = inst.poseAt(t);
    const double jaw = inst.jawAt(t);
    inst.driveByDevice(pose.frame, 1u, 5.0, jaw, t);
    // The hand starts where the script left the hinge, the jaws as they were, at rest.
    steer(i, pose.hinge, t);
  }
  return true;
}

void InstrumentSet::steer(int i, const Vec3& hinge, double t) {
  Instrument& inst = *instruments_[i];
  // Through a trocar the hand is the hinge's mirror through the port.
  const auto& trocar = inst.settings().trocar;
  inst.setHand(trocar ? Vec3(2.0 * *trocar - hinge) : hinge, Vec3::Zero(), t);
}

void InstrumentSet::moveJaws(int i, bool close, double t) { instruments_[i]->setJaws(close, t); }

bool InstrumentSet::turnNeedle(int i, double angle, double t, double duration) {
  Instrument& inst = *instruments_[i];
  if (!inst.drivenByDevice() || devices_[i] || inst.settings().trocar) return false;
  for (const auto& needle : needles_) {
    if (needle->holder != i) continue;
    // The needle where the jaws have it at t: its centre and its plane's normal (w).
    const RigidPose pose = jawsPose(inst.poseAt(t)) * needle->in_jaws;
    inst.turnAbout(pose.position, pose.rotation.col(2), angle, t, duration);
    return true;
  }
  return false;
}

void InstrumentSet::start() {
  for (auto& d : devices_)
    if (d) d->start();
}

void InstrumentSet::finish() {
  for (auto& d : devices_)
    if (d) d->finish();
}

bool InstrumentSet::threaded() const {
  for (const auto& d : devices_)
    if (d && d->threaded()) return true;
  return false;
}

bool InstrumentSet::interrupted() const {
  for (const auto& d : devices_)
    if (d && d->interrupted()) return true;
  return false;
}

std::string InstrumentSet::writeDeviceLogs(const std::string& directory) const {
  std::string lines;
  for (int i = 0; i < size(); ++i) {
    if (!devices_[i]) continue;
    const std::string file = "haptics_" + instruments_[i]->name() + ".csv";
    devices_[i]->writeCsv(directory + "/" + file);
    lines += "'" + instruments_[i]->name() + "' " + devices_[i]->summary() + " -> " + file + "\n";
  }
  return lines;
}

void InstrumentSet::openCsv(const std::string& path) {
  csv_.open(path);
  if (!csv_) throw std::runtime_error(path + ": cannot write");
  csv_.precision(9);
  csv_ << "time";
  for (const auto& inst : instruments_)
    for (const char* column : {"x", "y", "z", "jaw", "speed", "force", "holding"})
      csv_ << ',' << inst->name() << '_' << column;
  if (wound_) csv_ << ",wound_gap,wound_holes,needle_tissue_force";
  csv_ << '\n';
}

void InstrumentSet::measureSpecimen(const Scene& scene) {
  if (specimen_->layoutRevision() != specimen_revision_) {  // a layout change (cut, refine): the strands again
    specimen_revision_ = specimen_->layoutRevision();
    specimen_strands_ = strands(specimen_->basis());
  }
  if (specimen_strands_.size() < 2) return;
  // The strands not holding the kept end, each by chords over 64 pieces (O(h²): 1e-4 relative for
  // a strand bent at a radius of a fifth of its length); a strand's last point is its left limit.
  constexpr int kPieces = 64;
  double length = 0.0;
  BasisRow row;
  const VecX& q = scene.state().q;
  const auto at = [&](double s, bool from_left) {
    if (from_left)
      specimen_->basis().evaluateFromLeft(s, row);
    else
      specimen_->basis().evaluate(s, row);
    Vec3 x = Vec3::Zero();
    for (int j = 0; j < row.count; ++j) x += row.value[j] * q.segment<3>(3 * (specimen_->offset() + row.first + j));
    return x;
  };
  for (const Strand& strand : specimen_strands_) {
    if (specimen_kept_end_ >= strand.begin && specimen_kept_end_ <= strand.end) continue;
    Vec3 last = at(strand.begin, false);
    for (int k = 1; k <= kPieces; ++k) {
      const Vec3 next = at(strand.begin + (strand.end - strand.begin) * k / kPieces, k == kPieces);
      length += (next - last).norm();
      last = next;
    }
  }
  metrics_.setRemovedLength(length);
}

void InstrumentSet::writeSummary(const std::string& path, const nlohmann::json& knots) const {
  nlohmann::json out = metrics_.summary();
  if (wound_) out["wound"] = wound_->summary();
  if (!knots.is_null()) out["knots"] = knots;
  out["events"] = events_;
  std::ofstream file(path);
  file << out.dump(2) << '\n';
  file.close();
  if (!file) throw std::runtime_error(path + ": write failed");
}

}  // namespace filum::haptics
