#include "filum/haptics/wound.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "filum/collision/sphere_collision_model.hpp"
#include "filum/constraints/sliding_point_constraint.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/node.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/haptics/event_number.hpp"
#include "filum/geometry/closest_point.hpp"

namespace filum::haptics {

namespace {

/// The curve body at node `path`, or a SceneError at key `key` of p.
const CurveBody& curveNamed(const Scene& scene, const Params& p, const std::string& key, const std::string& path) {
  const MechanicalState* body = scene.bodyAt(path);
  if (!body || !body->curve()) p.fail(key, "the path of a node holding a curve body", "\"" + path + "\"");
  return *body->curve();
}

}  // namespace

Wound::Settings Wound::settingsFromParams(const Params& p, const Scene& scene) {
  Settings s;
  const nlohmann::json& lips = p.raw("lips");
  if (!lips.is_array() || lips.size() != 2 || !lips[0].is_string() || !lips[1].is_string())
    p.fail("lips", "two node paths, the lips' edge curves (e.g. [\"left lip\", \"right lip\"])", describeJson(lips));
  s.lips[0] = lips[0].get<std::string>();
  s.lips[1] = lips[1].get<std::string>();
  s.thread = p.string("thread");
  const CurveBody& a = curveNamed(scene, p, "lips", s.lips[0]);
  const CurveBody& b = curveNamed(scene, p, "lips", s.lips[1]);
  const CurveBody& thread = curveNamed(scene, p, "thread", s.thread);
  if (&a == &b) p.fail("lips", "two different lips", "\"" + s.lips[0] + "\" twice");
  if (&a == &thread || &b == &thread) p.fail("thread", "a thread that is not one of the lips", "\"" + s.thread + "\"");
  s.normal = p.vec3({"normal", "1"}, s.normal);
  if (!(s.normal.norm() > 0.0)) p.fail("normal", "a nonzero direction (the skin's outward normal)", "a zero vector");
  s.normal.normalize();
  s.width = p.positive({"width", "m"}, s.width);
  s.thickness = p.positive({"thickness", "m"}, s.thickness);
  s.edge_radius = p.nonNegative({"edge_radius", "m"}, s.edge_radius);
  if (2.0 * s.edge_radius >= std::min(s.width, s.thickness))
    p.fail("edge_radius", "less than half the lip's width and thickness", describeJson(p.raw({"edge_radius", "m"})));
  s.puncture_force = p.positive({"puncture_force", "N"}, s.puncture_force);
  s.indentation_stiffness = p.positive({"indentation_stiffness", "N/m"}, s.indentation_stiffness);
  s.holes_per_lip = p.integer("holes_per_lip", 1, kMaxHolesPerLip, s.holes_per_lip, "sliding points made per lip");
  s.friction = p.nonNegative({"friction", "N·s/m"}, s.friction);
  s.engage_distance = p.positive({"engage_distance", "m"}, s.engage_distance);
  if (p.has({"targets", "m"})) {
    const Points targets = p.points({"targets", "m"}, 1, kMaxTargets, "points marked on the skin");
    for (int i = 0; i < targets.rows(); ++i) s.targets.push_back(targets.row(i).transpose());
  }
  p.finish();
  return s;
}

Wound::Wound(Settings settings) : settings_(std::move(settings)) {}

void Wound::attach(Scene& scene, const std::string& origin) {
  origin_ = origin;
  MechanicalState* thread = scene.bodyAt(settings_.thread);
  for (int k = 0; k < 2; ++k) {
    for (int i = 0; i < settings_.holes_per_lip; ++i) {
      // Parked at the middle of both the thread and the lip until a hole engages it.
      auto c = std::make_unique<constraints::SlidingPointConstraint>(
          0.5, constraints::PointTarget::attached(settings_.lips[k], 0.5), settings_.friction);
      c->setName("wound hole " + std::to_string(k * settings_.holes_per_lip + i) + " (lip " + std::to_string(k) + ")");
      c->setOrigin(origin);
      c->setActive(false);
      slots_.push_back(c.get());
      thread->node()->addComponent(std::move(c));
    }
  }
  slot_used_.assign(slots_.size(), 0);
  auto pad = std::make_unique<WoundPad>(settings_.width, settings_.thickness, settings_.edge_radius);
  pad->setName("wound skin");
  pad->setOrigin(origin);
  pad_ = pad.get();
  scene.root().addComponent(std::move(pad));
}

void Wound::bind(const Scene& scene, const std::vector<std::unique_ptr<Needle>>& needles) {
  for (int k = 0; k < 2; ++k) lips_[k] = scene.bodyAt(settings_.lips[k])->curve();
  thread_ = scene.bodyAt(settings_.thread)->curve();
  if (!scene.collisionPipeline())
    throw SceneError(origin_, "a \"collision\" pipeline (ContactPipeline) for the skin to hold the thread and the lips "
                              "to meet", "none");
  std::vector<collision::SphereCollisionModel*> models;
  scene.root().collect(models);
  if (std::none_of(models.begin(), models.end(),
                   [&](const collision::SphereCollisionModel* m) { return &m->curve() == thread_; }))
    throw SceneError(origin_ + "/thread", "a SphereCollisionModel on the thread '" + settings_.thread +
                                              "' (the skin is an obstacle to it)", "none");
  carries_.assign(needles.size(), 0);
  for (std::size_t j = 0; j < needles.size(); ++j) {
    const MechanicalState* body = needles[j]->settings().thread.empty() ? nullptr : scene.bodyAt(needles[j]->settings().thread);
    carries_[j] = body && body->curve() == thread_;
  }
  if (std::find(carries_.begin(), carries_.end(), 1) == carries_.end())
    throw SceneError(origin_ + "/thread", "a needle carrying the thread '" + settings_.thread +
                                              "' (\"needles\": [{..., \"thread\": \"" + settings_.thread + "\"}])",
                     "none");
  // ô = ± n̂ × t̂ away from the other lip, decided at the middle of each lip at the start; the skin's
  // normal must cross each edge (|n̂ × t̂| >= ½ along it) for the slab to have a side.
  const SceneState& st = scene.state();
  for (int k = 0; k < 2; ++k) {
    for (int i = 0; i <= 8; ++i)
      if (settings_.normal.cross(lips_[k]->tangent(st.q, i / 8.0).normalized()).norm() < 0.5)
        throw SceneError(origin_ + "/normal", "the skin's normal across the lips' edges (at 30° or more to them)",
                         "one within 30° of lip '" + settings_.lips[k] + "' at s = " + eventNumber(i / 8.0));
    const Vec3 p = lips_[k]->position(st.q, 0.5), t = lips_[k]->tangent(st.q, 0.5).normalized();
    const Vec3 other = lips_[1 - k]->position(st.q, 0.5);
    side_[k] = settings_.normal.cross(t).dot(p - other) >= 0.0 ? 1.0 : -1.0;
  }
  gap_start_ = gap_min_ = gap_last_ = gap(st);
  updatePad(st, needles);
}

void Wound::updatePad(const SceneState& st, const std::vector<std::unique_ptr<Needle>>& needles) {
  // The edges at 32 stations each (a polyline: the pad's slabs within (L/31)² κ / 8 of the curve's),
  // into buffers sized once.
  constexpr int kStations = 32;
  for (int k = 0; k < 2; ++k) {
    edges_[k].resize(kStations);
    for (int i = 0; i < kStations; ++i) edges_[k][i] = edgeAt(st, k, static_cast<double>(i) / (kStations - 1));
  }
  pad_->setEdges(edges_[0], edges_[1]);
  // The thread in the tissue, stitch by stitch (a needle's holes from one entry into the skin to
  // the next; metres of thread to abscissa by |P'| at its middle):
  // - around each hole holding it, by the margin;
  // - between consecutive holding holes of one stitch (the thread between two stitches lies on
  //   the skin);
  // - from the current stitch's last holding hole on to the swaged end while a hole of that stitch
  //   is still on the needle's track ahead of the swage (the thread follows the needle in the
  //   tissue);
  // - the swaged end itself, which goes where the needle goes (the needle does not collide).
  const double per_metre = 1.0 / std::max(thread_->tangent(st.q, 0.5).norm(), 1e-12);
  const double margin = WoundPad::kHoleMargin * per_metre;
  spans_.clear();
  auto span = [&](double a, double b) { spans_.emplace_back(std::min(a, b) - margin, std::max(a, b) + margin); };
  for (std::size_t j = 0; j < needles.size(); ++j) {
    if (!carries_[j]) continue;
    const Hole* last = nullptr;  // the current stitch's last hole holding the thread
    bool ahead = false;          // a hole of the current stitch still ahead of the swage
    for (const Hole& h : holes_) {
      if (h.needle != static_cast<int>(j) || h.slot == kWithdrawn) continue;
      if (h.entry && h.face == Face::kSkin) {  // a new stitch: the thread before it lies on the skin
        last = nullptr;
        ahead = false;
      }
      if (h.slot == kPending && aheadOfSwage(st, h, *needles[j])) ahead = true;
      if (h.slot < 0 || slot_used_[h.slot] != 1) continue;
      const double s = slots_[h.slot]->abscissa(st);
      span(s, s);
      if (last) span(slots_[last->slot]->abscissa(st), s);
      last = &h;
    }
    const double end = needles[j]->settings().abscissa;
    if (ahead && last) span(slots_[last->slot]->abscissa(st), end);
    const double reach = Needle::kSwageLead * per_metre;
    span(end - reach, end + reach);
  }
  pad_->setPassage(thread_, spans_);
}

WoundPad::Station Wound::edgeAt(const SceneState& st, int k, double s) const {
  WoundPad::Station e;
  e.point = lips_[k]->position(st.q, s);
  e.tangent = lips_[k]->tangent(st.q, s).normalized();
  e.normal = (settings_.normal - settings_.normal.dot(e.tangent) * e.tangent).normalized();
  e.outward = side_[k] * e.normal.cross(e.tangent);
  e.velocity = lips_[k]->position(st.v, s);  // Ṗ(s) = Σ b_j(s) q̇_j
  return e;
}

Wound::LipPoint Wound::locate(const SceneState& st, int k, const Vec3& x) const {
  const CurveBody& lip = *lips_[k];
  const geometry::ClosestPoint cp = geometry::closestPoint(lip.basis(), lip.block(st.q), x);
  LipPoint l;
  const WoundPad::Station frame = edgeAt(st, k, cp.s);
  l.s = cp.s;
  l.edge = cp.point;
  l.tangent = frame.tangent;
  l.normal = frame.normal;
  l.outward = frame.outward;
  const Vec3 d = x - cp.point;
  l.across = d.dot(l.outward) + settings_.edge_radius;
  l.depth = -d.dot(l.normal) + settings_.edge_radius;
  l.inside = cp.s > 0.0 && cp.s < 1.0 && l.across >= 0.0 && l.across <= settings_.width && l.depth >= 0.0 &&
             l.depth <= settings_.thickness;
  return l;
}

Wound::Face Wound::nearestFace(const LipPoint& l, Vec3* inward) const {
  const double to[4] = {l.depth, l.across, settings_.thickness - l.depth, settings_.width - l.across};
  const Face faces[4] = {Face::kSkin, Face::kCut, Face::kBottom, Face::kFar};
  const Vec3 normals[4] = {-l.normal, l.outward, l.normal, -l.outward};
  int nearest = 0;
  for (int i = 1; i < 4; ++i)
    if (std::abs(to[i]) < std::abs(to[nearest])) nearest = i;
  if (inward) *inward = normals[nearest];
  return faces[nearest];
}

Vec3 Wound::crossing(const SceneState& st, int k, Vec3 a, Vec3 b, bool inside_a) const {
  // Bisection on [a, b]: 40 halvings leave 2⁻⁴⁰ of a step's motion (~0.1 mm), below round-off of
  // the positions (1e-16 of 0.1 m).
  for (int i = 0; i < 40; ++i) {
    const Vec3 m = 0.5 * (a + b);
    (locate(st, k, m).inside == inside_a ? a : b) = m;
  }
  return 0.5 * (a + b);
}

Vec3 Wound::holePosition(const SceneState& st, const Hole& h) const {
  return lips_[h.lip]->position(st.q, h.lip_abscissa) + h.offset;
}

namespace {
const char* faceName(Wound::Face f) {
  switch (f) {
    case Wound::Face::kSkin: return "skin";
    case Wound::Face::kCut: return "cut face";
    case Wound::Face::kBottom: return "underside";
    default: return "far side";
  }
}
}  // namespace

int Wound::makeHole(const SceneState& st, int k, const Vec3& at, bool entry, Face face, int needle, double depth,
                    std::vector<std::string>& events) {
  const LipPoint l = locate(st, k, at);
  Hole h;
  h.lip = k;
  h.lip_abscissa = l.s;
  h.offset = at - lips_[k]->position(st.q, h.lip_abscissa);
  h.entry = entry;
  h.face = face;
  h.time = st.time;
  h.needle = needle;
  h.from_edge = l.across;
  h.depth = depth;
  h.made_at = at;
  h.edge_tangent = l.tangent;
  h.skin_normal = l.normal;
  for (const Vec3& target : settings_.targets) {
    const double d = (target - at).norm();
    if (h.target_distance < 0.0 || d < h.target_distance) h.target_distance = d;
  }
  holes_.push_back(h);
  events.push_back(std::string("the needle ") + (entry ? "went into" : "came out of") + " lip " + std::to_string(k) +
                   " ('" + settings_.lips[k] + "') through its " + faceName(face) + " at s = " + eventNumber(h.lip_abscissa) +
                   ", " + eventNumber(1e3 * h.from_edge) + " mm from its cut face");
  return static_cast<int>(holes_.size()) - 1;
}

double Wound::pressingForce() const {
  double largest = 0.0;
  for (const Tip& tip : tips_) largest = std::max(largest, tip.force);
  return largest;
}

int Wound::holdingHoles() const {
  int count = 0;
  for (const char used : slot_used_) count += used == 1 ? 1 : 0;
  return count;
}

std::vector<std::string> Wound::afterStep(const SceneState& st) {
  gap_last_ = gap(st);
  gap_min_ = std::min(gap_min_, gap_last_);
  std::vector<std::string> events;
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    const bool holding = slots_[i]->active() && !slots_[i]->releasedAt(st);
    if (slot_used_[i] == 1 && !holding) {
      slot_used_[i] = 2;  // used, and let go for good
      events.push_back("the thread slid out of " + slots_[i]->name() + " at s = " + eventNumber(slots_[i]->abscissa(st)));
    }
  }
  return events;
}

std::vector<Wound::Stitch> Wound::stitches() const {
  // An entry into the skin, then (by the same needle) the next exit out of the skin: a stitch when
  // the two are in different lips. Both holes must not have been withdrawn.
  std::vector<Stitch> out;
  for (std::size_t i = 0; i < holes_.size(); ++i) {
    const Hole& a = holes_[i];
    if (!a.entry || a.face != Face::kSkin || a.slot == kWithdrawn) continue;
    double depth = 0.0;
    for (std::size_t j = i + 1; j < holes_.size(); ++j) {
      const Hole& b = holes_[j];
      if (b.needle != a.needle || b.slot == kWithdrawn) continue;
      if (!b.entry) depth = std::max(depth, b.depth);
      if (b.entry && b.face == Face::kSkin) break;  // a new stitch began
      if (b.entry || b.face != Face::kSkin) continue;
      if (b.lip != a.lip) {
        Stitch s;
        s.entry = static_cast<int>(i);
        s.exit = static_cast<int>(j);
        s.entry_bite = a.from_edge;
        s.exit_bite = b.from_edge;
        s.depth = depth;
        // The line between the holes as made, in the skin's plane there (⊥ the normal n̂ made ⊥ the
        // edge's tangent t̂ at the entry), against t̂: acos |t̂·ℓ̂| ∈ [0, π/2].
        const Vec3 n = a.skin_normal;  // ⊥ a.edge_tangent (locate)
        Vec3 line = b.made_at - a.made_at;
        line -= line.dot(n) * n;
        s.angle = line.norm() > 0.0 ? std::acos(std::min(1.0, std::abs(a.edge_tangent.dot(line.normalized())))) : 0.0;
        out.push_back(s);
      }
      break;
    }
  }
  return out;
}

nlohmann::json Wound::summary() const {
  nlohmann::json holes = nlohmann::json::array();
  for (const Hole& h : holes_) {
    nlohmann::json hole = {{"lip", settings_.lips[h.lip]}, {"kind", h.entry ? "entry" : "exit"},
                           {"face", faceName(h.face)}, {"time", h.time}, {"from_cut_face", h.from_edge},
                           {"held_thread", h.slot >= 0}, {"holds_thread", h.slot >= 0 && slot_used_[h.slot] == 1},
                           {"withdrawn", h.slot == kWithdrawn}};
    if (!h.entry) hole["depth"] = h.depth;
    if (h.target_distance >= 0.0) hole["target_distance"] = h.target_distance;
    holes.push_back(hole);
  }
  nlohmann::json stitches = nlohmann::json::array();
  for (const Stitch& s : this->stitches())
    stitches.push_back({{"entry_bite", s.entry_bite}, {"exit_bite", s.exit_bite}, {"depth", s.depth},
                        {"angle_deg", s.angle * 180.0 / M_PI}});
  return {{"holes", holes},
          {"stitches", stitches},
          {"holding", holdingHoles()},
          {"peak_needle_force", peak_force_},
          {"gap_start", gap_start_},
          {"gap_min", gap_min_},
          {"gap_end", gap_last_}};
}

std::string Wound::text() const {
  std::ostringstream out;
  out.precision(3);
  out << "  wound: " << holes_.size() << " holes (" << holdingHoles() << " hold the thread), gap " << 1e3 * gap_start_
      << " -> " << 1e3 * gap_last_ << " mm (smallest " << 1e3 * gap_min_ << "), peak needle force " << peak_force_
      << " N\n";
  for (const Stitch& s : stitches())
    out << "    stitch: bites " << 1e3 * s.entry_bite << " / " << 1e3 * s.exit_bite << " mm, " << 1e3 * s.depth
        << " mm deep, at " << s.angle * 180.0 / M_PI << " deg to the wound\n";
  return out.str();
}

double Wound::gap(const SceneState& st) const {
  const WoundPad::Station middle = edgeAt(st, 0, 0.5);  // −ô: across the wound, towards lip 1
  const geometry::ClosestPoint cp = geometry::closestPoint(lips_[1]->basis(), lips_[1]->block(st.q), middle.point);
  return -(cp.point - middle.point).dot(middle.outward) - 2.0 * settings_.edge_radius;
}

std::vector<std::string> Wound::follow(Scene& scene, const std::vector<std::unique_ptr<Needle>>& needles) {
  std::vector<std::string> events;
  const SceneState& st = scene.state();
  if (tips_.size() < needles.size()) tips_.resize(needles.size());
  for (std::size_t j = 0; j < needles.size(); ++j) {
    const Needle& needle = *needles[j];
    Tip& tip = tips_[j];
    const int index = static_cast<int>(j);
    const Vec3 x = needle.tip(needle.pose());
    if (!tip.started) {
      tip.started = true;
      tip.previous = x;
      for (int k = 0; k < 2; ++k)
        if (locate(st, k, x).inside) tip.in_lip = k;  // placed in the tissue: as if punctured
      continue;
    }
    tip.force = 0.0;
    if (tip.in_lip >= 0) {
      const LipPoint now = locate(st, tip.in_lip, x);
      if (now.inside) {
        tip.deepest = std::max(tip.deepest, now.depth);
      } else {
        const Vec3 at = crossing(st, tip.in_lip, tip.previous, x, true);
        const Face face = nearestFace(locate(st, tip.in_lip, at), nullptr);
        const int exit = makeHole(st, tip.in_lip, at, false, face, index, tip.deepest, events);
        holes_[exit].angle = angleOnNeedle(at, needle);
        // Drawn back out the way it went in: neither hole is a passage for the thread.
        if (tip.entry_hole >= 0) {
          Hole& in = holes_[tip.entry_hole];
          if (in.slot == kPending && in.face == face && (holePosition(st, in) - at).norm() <= settings_.engage_distance) {
            in.slot = kWithdrawn;
            holes_[exit].slot = kWithdrawn;
            events.push_back("the needle was drawn back out of lip " + std::to_string(tip.in_lip) +
                             " where it went in: no passage");
          }
        }
        tip.in_lip = -1;
        tip.entry_hole = -1;
      }
    }
    if (tip.pressing >= 0 && !locate(st, tip.pressing, x).inside) tip.pressing = -1;  // drawn back
    if (tip.in_lip < 0 && tip.pressing < 0) {
      for (int k = 0; k < 2; ++k) {
        if (!locate(st, k, x).inside) continue;
        tip.pressing = k;
        tip.entered = crossing(st, k, tip.previous, x, false);
        tip.face = nearestFace(locate(st, k, tip.entered), &tip.inward);
        break;
      }
    }
    if (tip.pressing >= 0) {
      // F = k_i δ, δ the depth past the entry along the entered face's inward normal.
      tip.force = settings_.indentation_stiffness * std::max(0.0, (x - tip.entered).dot(tip.inward));
      peak_force_ = std::max(peak_force_, tip.force);
      if (tip.force >= settings_.puncture_force) {
        tip.entry_hole = makeHole(st, tip.pressing, tip.entered, true, tip.face, index, 0.0, events);
        holes_[tip.entry_hole].angle = angleOnNeedle(tip.entered, needle);
        tip.in_lip = tip.pressing;
        tip.deepest = locate(st, tip.in_lip, x).depth;
        tip.pressing = -1;
        tip.force = 0.0;
      }
    }
    tip.previous = x;
  }
  engage(scene, needles, events);
  updatePad(scene.state(), needles);
  return events;
}

double Wound::angleOnNeedle(const Vec3& x, const Needle& needle) {
  // atan2 in the needle's plane, unwrapped about the arc's middle: θ ∈ [α/2 − π, α/2 + π], so that
  // points on the arc read 0 .. α whatever α (up to 2π).
  const Vec3 local = needle.pose().inverse().apply(x);
  const double middle = 0.5 * needle.settings().arc;
  return middle + std::remainder(std::atan2(local.y(), local.x()) - middle, 2.0 * M_PI);
}

bool Wound::aheadOfSwage(const SceneState& st, const Hole& h, const Needle& needle) const {
  const double angle = angleOnNeedle(holePosition(st, h), needle);
  return onNeedleTrack(st, h, needle) && angle >= -kEngageLag / needle.settings().radius &&
         angle <= needle.settings().arc;
}

bool Wound::onNeedleTrack(const SceneState& st, const Hole& h, const Needle& needle) const {
  // In the needle's frame (u, v, w): within engage_distance of its circle of radius R, radially and
  // out of its plane.
  const Vec3 local = needle.pose().inverse().apply(holePosition(st, h));
  return std::abs(std::hypot(local.x(), local.y()) - needle.settings().radius) <= settings_.engage_distance &&
         std::abs(local.z()) <= settings_.engage_distance;
}

double Wound::threadAtHole(const SceneState& st, const Needle& needle, const Vec3& X) const {
  // The thread's end at the swage, s_e, and the side the thread runs to from it.
  const double end = needle.settings().abscissa, toward = end < 0.5 ? 1.0 : -1.0;
  // Samples over 5 mm of thread from the swage (the hole is kEngageLag behind it), the nearest
  // refined by one projection on the tangent, s += tᵀ(X − P) / |t|².
  const double window = 5e-3 / std::max(thread_->tangent(st.q, end).norm(), 1e-12);
  double best_s = end, best = (thread_->position(st.q, end) - X).squaredNorm();
  for (int k = 1; k <= 100; ++k) {
    const double s = std::clamp(end + toward * window * k / 100.0, 0.0, 1.0);
    const double d = (thread_->position(st.q, s) - X).squaredNorm();
    if (d < best) {
      best = d;
      best_s = s;
    }
  }
  const Vec3 t = thread_->tangent(st.q, best_s);
  return std::clamp(best_s + t.dot(X - thread_->position(st.q, best_s)) / t.squaredNorm(), 0.0, 1.0);
}

void Wound::engage(Scene& scene, const std::vector<std::unique_ptr<Needle>>& needles, std::vector<std::string>& events) {
  for (Hole& h : holes_) {
    if (h.slot != kPending || !carries_[h.needle]) continue;
    const SceneState& st = scene.state();
    const Needle& needle = *needles[h.needle];
    const Vec3 X = holePosition(st, h);
    // The hole's angle in the needle's plane, from the swage towards the tip; the thread runs
    // through it once that falls below −kEngageLag / R between two steps (the swage kEngageLag
    // past it) from within the needle's arc, while the hole is on the needle's circle.
    const double angle = angleOnNeedle(X, needle), lag = -kEngageLag / needle.settings().radius;
    const bool passed = h.angle >= lag && h.angle <= needle.settings().arc && angle < lag;
    h.angle = angle;
    if (!passed) continue;
    if (!onNeedleTrack(st, h, needle)) {
      h.slot = kMissed;
      events.push_back("the needle's swage passed a hole of lip " + std::to_string(h.lip) +
                       " away from its track (the needle left its curve): the hole does not hold the thread");
      continue;
    }
    const double s_h = threadAtHole(st, needle, X);
    const double miss = (thread_->position(st.q, s_h) - X).norm();
    if (!(s_h > 0.0 && s_h < 1.0) || miss > settings_.engage_distance) {
      h.slot = kMissed;
      events.push_back("the needle's swage passed a hole of lip " + std::to_string(h.lip) + " but the thread is " +
                       eventNumber(1e3 * miss) + " mm from it (more than engage_distance): the hole does not hold the thread");
      continue;
    }
    int slot = kNoSlot;
    for (int i = 0; i < settings_.holes_per_lip; ++i) {
      const int index = h.lip * settings_.holes_per_lip + i;
      if (!slot_used_[index]) {
        slot = index;
        break;
      }
    }
    h.slot = slot;
    if (slot < 0) {
      events.push_back("the thread passed a hole of lip " + std::to_string(h.lip) + " but all its " +
                       std::to_string(settings_.holes_per_lip) +
                       " sliding points are used (raise \"holes_per_lip\"): it does not hold the thread");
      continue;
    }
    slot_used_[slot] = 1;
    constraints::SlidingPointConstraint& c = *slots_[slot];
    c.target().reattach(h.lip_abscissa, h.offset);
    c.rearm();
    c.setActive(true);
    // s(t) starts where the thread is in the hole, ṡ at its sliding rate: ġ's tangential part
    // vanishes, tᵀ(Ṗ(s) + t ṡ − Ẋ) = 0.
    SceneState next = st;
    const Vec3 t = thread_->tangent(st.q, s_h);
    const Vec3 pdot = thread_->position(st.v, s_h);  // Ṗ(s) = Σ b_j(s) q̇_j
    const Vec3 xdot = lips_[h.lip]->position(st.v, h.lip_abscissa);
    next.q[c.extraIndex()] = s_h;
    next.v[c.extraIndex()] = t.dot(xdot - pdot) / t.squaredNorm();
    scene.setState(next);
    events.push_back("the thread runs through the hole in lip " + std::to_string(h.lip) + " at s = " + eventNumber(s_h) +
                     " (" + c.name() + ")");
  }
}

}  // namespace filum::haptics
