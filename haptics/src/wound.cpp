#include "filum/haptics/wound.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "filum/constraints/sliding_point_constraint.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/node.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/closest_point.hpp"

namespace filum::haptics {

namespace {

std::string text(double x) {
  std::ostringstream out;
  out.precision(4);
  out << x;
  return out.str();
}

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
  p.finish();
  return s;
}

Wound::Wound(Settings settings) : settings_(std::move(settings)) {}

void Wound::attach(Scene& scene, const std::string& origin) {
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

void Wound::bind(const Scene& scene) {
  for (int k = 0; k < 2; ++k) lips_[k] = scene.bodyAt(settings_.lips[k])->curve();
  thread_ = scene.bodyAt(settings_.thread)->curve();
  // ô = ± n̂ × t̂ away from the other lip, decided at the middle of each lip at the start.
  const SceneState& st = scene.state();
  for (int k = 0; k < 2; ++k) {
    const Vec3 p = lips_[k]->position(st.q, 0.5), t = lips_[k]->tangent(st.q, 0.5).normalized();
    const Vec3 other = lips_[1 - k]->position(st.q, 0.5);
    side_[k] = settings_.normal.cross(t).dot(p - other) >= 0.0 ? 1.0 : -1.0;
  }
  gap_start_ = gap_min_ = gap_last_ = gap(st);
  updatePad(st, {});
}

void Wound::updatePad(const SceneState& st, const std::vector<std::unique_ptr<Needle>>& needles) {
  // The edges at 32 stations each (a polyline: the pad's slabs within (L/31)² κ / 8 of the curve's).
  constexpr int kStations = 32;
  std::vector<WoundPad::Station> edges[2];
  for (int k = 0; k < 2; ++k) {
    edges[k].resize(kStations);
    for (int i = 0; i < kStations; ++i) {
      const double s = static_cast<double>(i) / (kStations - 1);
      WoundPad::Station& station = edges[k][i];
      station.point = lips_[k]->position(st.q, s);
      station.tangent = lips_[k]->tangent(st.q, s).normalized();
      station.normal = (settings_.normal - settings_.normal.dot(station.tangent) * station.tangent).normalized();
      station.outward = side_[k] * station.normal.cross(station.tangent);
      station.velocity = lips_[k]->position(st.v, s);
    }
  }
  pad_->setEdges(std::move(edges[0]), std::move(edges[1]));
  // The thread in the tissue: between its holding holes, and on to its swaged end while a needle
  // has holes its swage has not reached (the thread follows it in the tissue), widened by the margin.
  double lo = 2.0, hi = -1.0;
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    if (slot_used_[i] != 1) continue;
    const double s = slots_[i]->abscissa(st);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  if (hi >= lo)
    for (const Hole& h : holes_)
      if (h.slot == -1 && h.needle < static_cast<int>(needles.size())) {
        const double end = needles[h.needle]->settings().abscissa;
        lo = std::min(lo, end);
        hi = std::max(hi, end);
      }
  // |P'| at the middle of the thread: metres of thread per unit of abscissa.
  const double per_metre = 1.0 / std::max(thread_->tangent(st.q, 0.5).norm(), 1e-12);
  std::vector<std::pair<double, double>> spans;
  if (hi >= lo) spans.emplace_back(lo - WoundPad::kHoleMargin * per_metre, hi + WoundPad::kHoleMargin * per_metre);
  // The thread's end in the swage goes where the needle goes (the needle does not collide): its
  // swaged length and the margin.
  for (const auto& needle : needles) {
    if (needle->settings().thread != settings_.thread) continue;
    const double end = needle->settings().abscissa;
    const double reach = (Needle::kSwageLead + WoundPad::kHoleMargin) * per_metre;
    spans.emplace_back(end - reach, end + reach);
  }
  pad_->setPassage(thread_, std::move(spans));
}

Wound::LipPoint Wound::locate(const SceneState& st, int k, const Vec3& x) const {
  const CurveBody& lip = *lips_[k];
  const geometry::ClosestPoint cp = geometry::closestPoint(lip.basis(), lip.block(st.q), x);
  LipPoint l;
  l.s = cp.s;
  l.edge = cp.point;
  l.tangent = lip.tangent(st.q, cp.s).normalized();
  l.normal = (settings_.normal - settings_.normal.dot(l.tangent) * l.tangent).normalized();
  l.outward = side_[k] * l.normal.cross(l.tangent);
  const Vec3 d = x - cp.point;
  l.across = d.dot(l.outward) + settings_.edge_radius;
  l.depth = -d.dot(l.normal) + settings_.edge_radius;
  l.inside = cp.s > 0.0 && cp.s < 1.0 && l.across >= 0.0 && l.across <= settings_.width && l.depth >= 0.0 &&
             l.depth <= settings_.thickness;
  return l;
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

void Wound::makeHole(const SceneState& st, int k, const Vec3& at, bool entry, int needle,
                     std::vector<std::string>& events) {
  Hole h;
  h.lip = k;
  h.lip_abscissa = locate(st, k, at).s;
  h.offset = at - lips_[k]->position(st.q, h.lip_abscissa);
  h.entry = entry;
  h.time = st.time;
  h.needle = needle;
  h.from_edge = locate(st, k, at).across;
  holes_.push_back(h);
  events.push_back(std::string("the needle ") + (entry ? "punctured" : "came out of") + " lip " +
                   std::to_string(k) + " ('" + settings_.lips[k] + "') at s = " + text(h.lip_abscissa) + ", " +
                   text(1e3 * h.from_edge) + " mm from its edge");
}

double Wound::pressingForce(int needle) const {
  return needle < static_cast<int>(tips_.size()) ? tips_[needle].force : 0.0;
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
      events.push_back("the thread slid out of " + slots_[i]->name() + " at s = " + text(slots_[i]->abscissa(st)));
    }
  }
  return events;
}

nlohmann::json Wound::summary() const {
  nlohmann::json holes = nlohmann::json::array();
  for (const Hole& h : holes_)
    holes.push_back({{"lip", settings_.lips[h.lip]}, {"kind", h.entry ? "entry" : "exit"}, {"time", h.time},
                     {"from_edge", h.from_edge}, {"holds_thread", h.slot >= 0}});
  return {{"holes", holes},
          {"holding", holdingHoles()},
          {"peak_needle_force", peak_force_},
          {"gap_start", gap_start_},
          {"gap_min", gap_min_},
          {"gap_end", gap_last_}};
}

double Wound::gap(const SceneState& st) const {
  const Vec3 p = lips_[0]->position(st.q, 0.5);
  const Vec3 t = lips_[0]->tangent(st.q, 0.5).normalized();
  const Vec3 n = (settings_.normal - settings_.normal.dot(t) * t).normalized();
  const Vec3 toward = -side_[0] * n.cross(t);  // across the wound, towards lip 1
  const geometry::ClosestPoint cp = geometry::closestPoint(lips_[1]->basis(), lips_[1]->block(st.q), p);
  return (cp.point - p).dot(toward) - 2.0 * settings_.edge_radius;
}

std::vector<std::string> Wound::follow(Scene& scene, const std::vector<std::unique_ptr<Needle>>& needles) {
  std::vector<std::string> events;
  const SceneState& st = scene.state();
  if (tips_.size() < needles.size()) tips_.resize(needles.size());
  for (std::size_t j = 0; j < needles.size(); ++j) {
    const Needle& needle = *needles[j];
    Tip& tip = tips_[j];
    const Vec3 x = needle.tip(needle.pose());
    if (!tip.started) {
      tip.started = true;
      tip.previous = x;
      for (int k = 0; k < 2; ++k)
        if (locate(st, k, x).inside) tip.in_lip = k;  // placed in the tissue: as if punctured
      continue;
    }
    tip.force = 0.0;
    if (tip.in_lip >= 0 && !locate(st, tip.in_lip, x).inside) {
      makeHole(st, tip.in_lip, crossing(st, tip.in_lip, tip.previous, x, true), false, static_cast<int>(j), events);
      tip.in_lip = -1;
    }
    if (tip.pressing >= 0 && !locate(st, tip.pressing, x).inside) tip.pressing = -1;  // drawn back
    if (tip.in_lip < 0 && tip.pressing < 0) {
      for (int k = 0; k < 2; ++k) {
        const LipPoint now = locate(st, k, x);
        if (!now.inside) continue;
        tip.pressing = k;
        tip.entered = crossing(st, k, tip.previous, x, false);
        // The entered face: the boundary nearest to e in the slab's coordinates, its inward normal.
        const LipPoint e = locate(st, k, tip.entered);
        const double to_top = e.depth, to_cut = e.across, to_bottom = settings_.thickness - e.depth,
                     to_far = settings_.width - e.across;
        const double nearest = std::min({to_top, to_cut, to_bottom, to_far});
        tip.inward = nearest == to_top ? Vec3(-e.normal)
                     : nearest == to_cut ? e.outward
                     : nearest == to_bottom ? e.normal
                                            : Vec3(-e.outward);
        break;
      }
    }
    if (tip.pressing >= 0) {
      // F = k_i δ, δ the depth past the entry along the entered face's inward normal.
      tip.force = settings_.indentation_stiffness * std::max(0.0, (x - tip.entered).dot(tip.inward));
      peak_force_ = std::max(peak_force_, tip.force);
      if (tip.force >= settings_.puncture_force) {
        makeHole(st, tip.pressing, tip.entered, true, static_cast<int>(j), events);
        tip.in_lip = tip.pressing;
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

double Wound::threadAtHole(const SceneState& st, const Needle& needle, const Vec3& X) const {
  // The thread's end at the swage, s_e, and the side the thread runs to from it.
  const double end = needle.settings().abscissa, toward = end < 0.5 ? 1.0 : -1.0;
  // Samples over 5 mm of thread from the swage (the hole is within one step's motion of it, ~0.1 mm),
  // the nearest refined by one projection on the tangent, s += tᵀ(X − P) / |t|².
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
  const double nearest = best_s + t.dot(X - thread_->position(st.q, best_s)) / t.squaredNorm();
  // The thread near its end need not yet lie along the needle's track (its end only follows the
  // swage's hold): then its nearest point is the end itself. The hole is behind the swage by
  // |X − swage|; so much thread at least has passed it.
  const double passed = end + toward * (needle.swage(needle.pose()) - X).norm() /
                                  std::max(thread_->tangent(st.q, end).norm(), 1e-12);
  return std::clamp(toward > 0.0 ? std::max(nearest, passed) : std::min(nearest, passed), 0.0, 1.0);
}

void Wound::engage(Scene& scene, const std::vector<std::unique_ptr<Needle>>& needles, std::vector<std::string>& events) {
  for (Hole& h : holes_) {
    if (h.slot != -1) continue;
    const SceneState& st = scene.state();
    const Vec3 X = holePosition(st, h);
    // The needle runs along its own arc through the holes it made: once the hole is behind the
    // swage (its angle in the needle's plane, from the swage towards the tip, below 0), the thread
    // runs through it.
    const Needle& needle = *needles[h.needle];
    const Vec3 local = needle.pose().inverse().apply(X);
    if (std::atan2(local.y(), local.x()) >= 0.0) continue;
    const double s_h = threadAtHole(st, needle, X);
    const double miss = (thread_->position(st.q, s_h) - X).norm();
    if (!(s_h > 0.0 && s_h < 1.0) || miss > settings_.engage_distance) {
      h.slot = -2;
      events.push_back("the needle's swage passed a hole of lip " + std::to_string(h.lip) + " but the thread is " +
                       text(1e3 * miss) + " mm from it (more than engage_distance): the hole does not hold the thread");
      continue;
    }
    const geometry::ClosestPoint cp{s_h, thread_->position(st.q, s_h), miss};
    int slot = -2;  // none free
    for (int i = 0; i < settings_.holes_per_lip; ++i) {
      const int index = h.lip * settings_.holes_per_lip + i;
      if (!slot_used_[index]) {
        slot = index;
        break;
      }
    }
    h.slot = slot;
    if (slot < 0) {
      h.slot = -3;
      events.push_back("the thread passed a hole of lip " + std::to_string(h.lip) +
                       " but all its " + std::to_string(settings_.holes_per_lip) +
                       " sliding points are used (raise \"holes_per_lip\"): it does not hold the thread");
      continue;
    }
    slot_used_[slot] = 1;
    constraints::SlidingPointConstraint& c = *slots_[slot];
    c.target().reattach(h.lip_abscissa, h.offset);
    c.setActive(true);
    // s(t) starts where the thread is in the hole, ṡ at its sliding rate: ġ's tangential part
    // vanishes, tᵀ(Ṗ(s) + t ṡ − Ẋ) = 0.
    SceneState next = st;
    const Vec3 t = thread_->tangent(st.q, cp.s);
    const Vec3 pdot = thread_->position(st.v, cp.s);  // Ṗ(s) = Σ b_j(s) q̇_j
    const Vec3 xdot = lips_[h.lip]->position(st.v, h.lip_abscissa);
    next.q[c.extraIndex()] = cp.s;
    next.v[c.extraIndex()] = t.dot(xdot - pdot) / t.squaredNorm();
    scene.setState(next);
    events.push_back("the thread runs through the hole in lip " + std::to_string(h.lip) +
                     " at s = " + text(cp.s) + " (" + c.name() + ")");
  }
}

}  // namespace filum::haptics
