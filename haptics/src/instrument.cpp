#include "filum/haptics/instrument.hpp"

#include <algorithm>
#include <cmath>

#include "filum/core/curve_body.hpp"

namespace filum::haptics {

const char* instrumentKindName(InstrumentKind kind) {
  switch (kind) {
    case InstrumentKind::kGrasper: return "Grasper";
    case InstrumentKind::kScissors: return "Scissors";
    case InstrumentKind::kBipolarForceps: return "BipolarForceps";
    case InstrumentKind::kNeedleHolder: return "NeedleHolder";
  }
  return "?";
}

InstrumentSettings InstrumentSettings::fromParams(const Params& p) {
  InstrumentSettings s;
  s.name = p.string("name");
  const std::string type = p.string("type");
  if (type == "Grasper") {
    s.kind = InstrumentKind::kGrasper;
  } else if (type == "Scissors") {
    s.kind = InstrumentKind::kScissors;
  } else if (type == "BipolarForceps") {
    s.kind = InstrumentKind::kBipolarForceps;
  } else if (type == "NeedleHolder") {
    s.kind = InstrumentKind::kNeedleHolder;
    s.holding_force = 5.0;
  } else {
    p.fail("type", "\"Grasper\", \"Scissors\", \"BipolarForceps\" or \"NeedleHolder\"", "\"" + type + "\"");
  }
  s.shape.shaft_length = p.positive({"shaft_length", "m"}, s.shape.shaft_length);
  s.shape.shaft_radius = p.positive({"shaft_radius", "m"}, s.shape.shaft_radius);
  s.shape.jaw_length = p.positive({"jaw_length", "m"}, s.shape.jaw_length);
  s.shape.jaw_radius = p.positive({"jaw_radius", "m"}, s.shape.jaw_radius);
  s.shape.max_angle = p.positive({"max_angle", "rad"}, s.shape.max_angle);
  // Jaws wider than a straight angle would fold back onto the shaft.
  if (s.shape.max_angle > M_PI) p.fail("max_angle", "an angle in (0, π] (rad) between the jaws fully open");
  s.close_below = p.number({"close_below", "1"}, s.close_below);
  if (!(s.close_below > 0.0 && s.close_below < 1.0)) p.fail("close_below", "an opening in (0, 1)");
  s.holding_force = p.positive({"holding_force", "N"}, s.holding_force);
  s.grasp_stiffness = p.positive({"grasp_stiffness", "N/m"}, s.grasp_stiffness);
  s.grasp_damping = p.nonNegative({"grasp_damping", "N·s/m"}, -1.0);
  if (!p.has("grasp_damping")) s.grasp_damping = -1.0;
  s.coagulation_time = p.positive({"coagulation_time", "s"}, s.coagulation_time);
  if (p.has("require_coagulation") && p.raw("require_coagulation").is_array()) {
    const nlohmann::json& list = p.raw("require_coagulation");
    for (std::size_t k = 0; k < list.size(); ++k) {
      if (!list[k].is_string())
        p.fail("require_coagulation", "true, false, or a list of node paths (\"tube\")", describeJson(list[k]));
      s.coagulation_objects.push_back(list[k].get<std::string>());
    }
    s.require_coagulation = !s.coagulation_objects.empty();
  } else {
    s.require_coagulation = p.boolean("require_coagulation", false);
  }
  s.force_limit = p.positive({"force_limit", "N"}, s.force_limit);
  s.collide = p.boolean("collide", true);
  if (p.has("trocar")) s.trocar = p.vec3({"trocar", "m"});
  s.device = p.has("device");  // read by InstrumentSet (it builds the device)
  if (s.device && p.has("path")) p.fail("path", "a path or a device driving the instrument, not both", "both");
  if (!s.device) s.path = InstrumentPath::fromParams(p, "path", s.trocar ? &*s.trocar : nullptr);
  if (s.trocar && !s.device) {
    // The hinge within the shaft's reach of the port over the whole path, sampled every 1 ms and
    // at its end.
    const double end = s.path.endTime();
    for (long k = 0; k <= static_cast<long>(end * 1e3) + 1; ++k) {
      const double t = std::min(end, 1e-3 * k);
      const double reach = (s.path.hinge(t) - *s.trocar).norm();
      if (reach > s.shape.shaft_length)
        p.fail("trocar", "a port within shaft_length (" + describeJson(s.shape.shaft_length) +
                             " m) of the hinge all along the path (the shaft passes through it)",
               "the hinge " + describeJson(reach) + " m away at t = " + describeJson(t) + " s");
    }
  }
  if (s.kind != InstrumentKind::kGrasper && s.kind != InstrumentKind::kNeedleHolder && p.has("holding_force"))
    p.fail("holding_force", "no holding force on a " + type + " (only a Grasper's and a NeedleHolder's jaws let a thread slip)",
           "one");
  if (s.kind != InstrumentKind::kBipolarForceps && p.has("coagulation_time"))
    p.fail("coagulation_time", "no coagulation time on a " + type + " (only BipolarForceps coagulate)", "one");
  if (s.device && (p.has("grasp_stiffness") || p.has("grasp_damping")))
    p.fail(p.has("grasp_stiffness") ? "grasp_stiffness" : "grasp_damping",
           "no grasp gains with a device: its coupling's (\"device\": {\"coupling\": {\"stiffness\", \"damping\"}}) are "
           "the hold the hand feels through",
           "one");
  if (s.kind != InstrumentKind::kScissors && p.has("require_coagulation"))
    p.fail("require_coagulation", "require_coagulation only on Scissors", type);
  p.finish();
  return s;
}

std::optional<JawCatch> catchBetweenJaws(const Scene& scene, const InstrumentShape& shape, const InstrumentPose& pose,
                                         double before, double now) {
  std::optional<JawCatch> best;
  const VecX& q = scene.state().q;
  for (const MechanicalState* body : scene.bodies()) {
    const CurveBody* curve = body->curve();
    if (!curve) continue;
    // Caught: between the jaws before this step, closed onto now; the distance to the midline.
    // The thread's radius r is its section's at s (a rod's spans: a thin tip slips out of jaws
    // closed onto the shaft's section).
    auto caught = [&](double s) {
      const Vec3 x = curve->position(q, s);
      const double r = curve->radiusAt(s);
      const double d = betweenJaws(shape, pose, before, x, r);
      if (d < 0.0 || !jawsClosedOn(shape, now, jawCoordinates(pose, x).along, r)) return -1.0;
      return d;
    };
    const int m = std::max(64, 8 * curve->pointCount());
    const double step = 1.0 / (m - 1);
    int found = -1;
    double nearest = 0.0;
    for (int k = 0; k < m; ++k) {
      const double d = caught(k * step);
      if (d >= 0.0 && (found < 0 || d < nearest)) {
        found = k;
        nearest = d;
      }
    }
    if (found < 0) continue;
    // Golden-section search of the distance to the midline on the sample's neighbourhood
    // (unimodal there for a thread straighter than the sampling: 8 samples per control point).
    auto midline = [&](double s) {
      const JawCoordinates c = jawCoordinates(pose, curve->position(q, s));
      return std::hypot(c.lateral, c.across);
    };
    double lo = std::max(0.0, (found - 1) * step), hi = std::min(1.0, (found + 1) * step);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 40; ++it) {  // 0.618^40 ≈ 4e-9 of the bracket
      const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
      if (midline(a) < midline(b)) {
        hi = b;
      } else {
        lo = a;
      }
    }
    double s = 0.5 * (lo + hi);
    double d = caught(s);
    if (d < 0.0) {  // the refined point left the jaws (at their edge): keep the sample
      s = found * step;
      d = nearest;
    }
    if (!best || d < best->distance) best = JawCatch{curve, s, d, jawCoordinates(pose, curve->position(q, s)).along};
  }
  return best;
}

Instrument::Instrument(InstrumentSettings settings) : settings_(std::move(settings)) {
  hold_->touching = false;  // the jaws act by their hold only; pushing is the parts' contact
  hold_->grasp_stiffness = settings_.grasp_stiffness;
  hold_->grasp_damping = settings_.grasp_damping;
  hold_->radius = settings_.shape.jaw_radius;
}

std::unique_ptr<InstrumentCapsule> Instrument::makePart(int index) {
  auto part = std::make_unique<InstrumentCapsule>();
  part->setName(settings_.name + (index == 0 ? " shaft" : index == 1 ? " jaw +" : " jaw -"));
  parts_[index] = part.get();
  return part;
}

Capsule Instrument::partNow(int index) const {
  if (index == 0) return settings_.shape.shaft(pose_);
  return settings_.shape.jaw(pose_, opening_, index == 1 ? 1 : -1);
}

bool Instrument::jawsCollide() const {
  if (!settings_.collide || settings_.kind == InstrumentKind::kScissors || holds_object_) return false;
  if (holding()) return held_span_;
  return jaws_clear_ && opening_ <= settings_.close_below;
}

void Instrument::setHeldSpan(double from, double to) {
  held_span_ = holding();
  for (int i = 1; i < kParts; ++i) {
    if (!parts_[i]) continue;
    parts_[i]->setPassage(held_span_ ? hold_->grasp.body() : nullptr, from, to);
    parts_[i]->setEnabled(jawsCollide());
  }
}

void Instrument::holdObject() {
  holds_object_ = true;
  hold_opening_ = opening_;
  for (int i = 1; i < kParts; ++i)
    if (parts_[i]) parts_[i]->setEnabled(false);
}

void Instrument::releaseObject() {
  holds_object_ = false;
  jaws_clear_ = opening_ > settings_.close_below;
  for (int i = 1; i < kParts; ++i)
    if (parts_[i]) parts_[i]->setEnabled(jawsCollide());
}

void Instrument::driveByDevice(const Eigen::Matrix3d& frame, unsigned buttons, double jaw_speed, double jaw,
                               double time) {
  drive_ = DeviceDrive{};
  drive_->frame = frame;
  drive_->buttons = buttons;
  drive_->jaw_speed = jaw_speed;
  drive_->jaw = jaw;
  drive_->jaw_time = time;
}

void Instrument::setStylus(const Vec3& position, const Vec3& velocity, double time, unsigned buttons) {
  if (!drive_) return;
  setJaws((buttons & drive_->buttons) != 0, time);
  setHand(position, velocity, time);
}

void Instrument::setHand(const Vec3& position, const Vec3& velocity, double time) {
  if (!drive_) return;
  bakeTurn(time);
  drive_->position = position;
  drive_->velocity = velocity;
  drive_->time = time;
}

void Instrument::bakeTurn(double time) {
  if (!drive_ || !drive_->turn) return;
  // The turn stops where it has got to at `time`: its frame kept, and the hinge's swing about the
  // centre kept as an offset from the hand (the hand's next stroke moves the jaws from there,
  // without a jump).
  const InstrumentPose turned = drivenPose(time);
  drive_->turn.reset();
  const InstrumentPose unturned = drivenPose(time);
  drive_->frame = turned.frame;
  drive_->hand_offset += turned.hinge - unturned.hinge;
}

void Instrument::setJaws(bool closing, double time) {
  if (!drive_) return;
  DeviceDrive& d = *drive_;
  d.jaw = jawAt(time);
  d.jaw_time = std::max(time, d.jaw_time);
  d.moving = true;
  d.closing = closing;
}

double Instrument::jawAt(double t) const {
  if (!drive_) return settings_.path.jaw(t);
  const DeviceDrive& d = *drive_;
  if (!d.moving) return d.jaw;  // taken over by the hand: as they were until a key moves them
  return std::clamp(d.jaw + (d.closing ? -1.0 : 1.0) * d.jaw_speed * std::max(0.0, t - d.jaw_time), 0.0, 1.0);
}

InstrumentPose Instrument::drivenPose(double t) const {
  const Vec3 hand = drive_->position + drive_->velocity * (t - drive_->time);
  InstrumentPose pose;
  pose.hinge = (settings_.trocar ? Vec3(2.0 * *settings_.trocar - hand) : hand) + drive_->hand_offset;
  pose.frame = drive_->frame;
  if (drive_->turn) {
    // x → c + R(φ) (x − c), R(φ) the turn by φ = angle · progress(t) about the axis.
    const DeviceDrive::Turn& turn = *drive_->turn;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(turn.angle * turn.progress(t), turn.axis).toRotationMatrix();
    pose.hinge = turn.centre + R * (pose.hinge - turn.centre);
    pose.frame = R * pose.frame;
  }
  return pose;
}

void Instrument::turnAbout(const Vec3& centre, const Vec3& axis, double angle, double time, double duration) {
  if (!drive_) return;
  // A turn about the same axis still under way adds what it had left to go (key presses add up);
  // the turn so far is made part of the drive, then the new one runs from `time`.
  const Vec3 unit = axis.normalized();
  if (drive_->turn && (drive_->turn->centre - centre).norm() <= 1e-12 && (drive_->turn->axis - unit).norm() <= 1e-12) {
    angle += drive_->turn->angle * (1.0 - drive_->turn->progress(time));
  }
  bakeTurn(time);
  drive_->turn = DeviceDrive::Turn{centre, unit, angle, time, duration};
}

InstrumentPose Instrument::poseAt(double t) const {
  InstrumentPose pose;
  if (drive_) {
    pose = drivenPose(t);
    if (settings_.trocar) {
      // The hand cannot pull the jaws out through the port nor push the shaft past its length:
      // the hinge kept between 1 mm and shaft_length from the port (a scripted path is checked
      // at load instead).
      const Vec3 r = pose.hinge - *settings_.trocar;
      const double reach = r.norm(), lo = 1e-3, hi = settings_.shape.shaft_length;
      if (reach > hi) pose.hinge = *settings_.trocar + r * (hi / reach);
      if (reach < lo) pose.hinge = *settings_.trocar + (reach > 0.0 ? Vec3(r / reach) : Vec3(pose.axis())) * lo;
    }
  } else {
    pose = settings_.path.pose(t);
  }
  if (settings_.trocar) {
    // Laparoscopy: the axis through the port, by the least rotation of the path's frame.
    const Vec3 axis = (pose.hinge - *settings_.trocar).normalized();
    pose.frame = Eigen::Quaterniond::FromTwoVectors(pose.axis(), axis).toRotationMatrix() * pose.frame;
  }
  return pose;
}

void Instrument::setTime(double t, double h) {
  pose_ = poseAt(t);
  previous_opening_ = previous_opening_ < 0.0 ? jawAt(t) : opening_;
  opening_ = jawAt(t);
  if (opening_ > previous_opening_) latched_ = false;
  // Jaws that let go of something closed on it stay clear of collisions until they have opened.
  if (opening_ > settings_.close_below) jaws_clear_ = true;
  next_ = poseAt(t + h);
  h_ = h;
  const double next_opening = jawAt(t + h);
  const InstrumentShape& shape = settings_.shape;
  for (int i = 0; i < kParts; ++i) {
    if (!parts_[i]) continue;
    const Capsule now = partNow(i);
    const Capsule end = i == 0 ? shape.shaft(next_) : shape.jaw(next_, next_opening, i == 1 ? 1 : -1);
    parts_[i]->setMotion(now, end, t, h);
    parts_[i]->setEnabled(settings_.collide && (i == 0 || jawsCollide()));
  }
  hold_->time = t;
  aimHold();
}

void Instrument::aimHold() {
  // The held point's target X moves with the jaws: X(t') = X + Ẋ (t' − t) over the step.
  hold_->position = anchor(pose_);
  hold_->velocity = (anchor(next_) - hold_->position) / h_;
}

void Instrument::startHolding(const CurveBody& body, double abscissa, double along) {
  anchor_along_ = std::clamp(along, 0.0, settings_.shape.jaw_length);
  hold_opening_ = opening_;
  held_for_ = 0.0;
  grasp(*hold_, body, abscissa);
  aimHold();
  held_span_ = false;  // until setHeldSpan says which piece the jaws hold
  for (int i = 1; i < kParts; ++i)
    if (parts_[i]) parts_[i]->setEnabled(false);
}

void Instrument::stopHolding() {
  release(*hold_);
  held_for_ = 0.0;
  held_span_ = false;
  jaws_clear_ = opening_ > settings_.close_below;
  for (int i = 1; i < kParts; ++i) {
    if (!parts_[i]) continue;
    parts_[i]->setPassage(nullptr, 0.0, 0.0);
    parts_[i]->setEnabled(jawsCollide());
  }
}

}  // namespace filum::haptics
