// Instrument: one surgical instrument of a scene's "instruments" list — its kind, shape and
// driver (the model), where it is and what its jaws hold (the state), and its parts as obstacles
// of the collision pipeline. InstrumentSet (instrument_set.hpp) runs them between the steps.
//
//   {"name": "left", "type": "Grasper" | "Scissors" | "BipolarForceps" | "NeedleHolder",
//    "path": [keyframes: instrument_path.hpp]     a script, or
//    "device": {a "haptics" block without "tool" (haptic_session.hpp): "device", "frame", "limits",
//               "coupling", "rate", "mode", ...; and "button": 1 (held: the jaws close),
//               "jaw_speed": 5 (1/s), "direction": [x, y, z] and "roll": rad (the shaft's fixed
//               orientation: a 3-DOF stylus gives the hinge's position only)},
//    "shaft_length": m, "shaft_radius": m, "jaw_length": m, "jaw_radius": m, "max_angle": rad,
//    "close_below": 0.15,       jaws that reach this opening holding nothing have missed; closed
//                               this far on nothing, graspers' and forceps' jaws push threads
//    "holding_force": N,        Grasper, NeedleHolder: the pull along a thread the jaws hold
//                               (default 2 N; 5 N for a needle holder)
//    "grasp_stiffness": N/m, "grasp_damping": N·s/m   the jaws' hold on the point (500; critical;
//                               with a device, its coupling's gains instead)
//    "coagulation_time": s,     BipolarForceps: closed this long on a tube, the span is coagulated
//    "require_coagulation": true | ["node", ...]   Scissors: a cut outside a coagulated span (of
//                               every body, or of the named nodes' bodies) is refused (an error)
//    "force_limit": N,          the force on tissue above which the metrics count the time
//    "collide": true,           the shaft and jaws push threads (needs a collision pipeline)
//    "trocar": [x, y, z]}       a fixed port the shaft passes through (laparoscopy): the path's
//                               keyframes then give no direction, the shaft's axis runs from the
//                               port to the hinge at every instant (the frame turned from the
//                               path's by the least rotation that does it), and the hinge stays
//                               within shaft_length of the port
//
// What the jaws do (instrument_set.cpp). At every step in which they close (the opening falls),
// the jaws catch the thread that was between them (betweenJaws at the previous step's opening,
// instrument_shape.hpp) once they have closed onto it (jawsClosedOn: the gap between their
// surfaces at its place is down to its diameter) — the point of it nearest to their midline:
//   Grasper: holds that point: the coupling F = k (X − P(s*)) + c (Ẋ − Ṗ(s*)) of haptics/tool.hpp
//     to the point X of the jaws' midline where it was caught; a spring–slider: when the pull
//     along the thread |F·t̂| exceeds the holding force, the thread slips through the jaws, s*
//     moving by (|F·t̂| − F_hold) / (k |P'(s*)|) so that the jaws again bear F_hold (t̂ = P'/|P'|);
//     pulled past the thread's end, it is let go. Opening the jaws (wider than when they caught)
//     lets go.
//   BipolarForceps: clamps the point the same way, without slipping; closed for coagulation_time,
//     the span under its jaws (s* ± jaw_length / 2 |P'|) is coagulated.
//   Scissors: cut the thread at s* (Scene::cut) at that step; once per closing (they cut again
//     after opening).
//   NeedleHolder: takes a needle (needle.hpp) whose wire is between its jaws, rigidly, from
//     whoever held it; with no needle there, holds a thread as a grasper does. Opening lets go.
// Jaws that reach close_below holding nothing have missed (a grasper's missed grasp). Collision:
// the shaft always pushes threads; the jaws of a grasper or forceps only when closed (at or
// below close_below) on nothing — open, the space between them is where a thread is caught — or
// when they hold a thread: then the piece of it between them (the held point ± a jaw's length,
// its radius and the thread's: setHeldSpan) passes, the hold being its contact, and everything
// else is pushed; holding a needle, they do not push; scissors' blades never push (they cut what
// is between them).
#pragma once

#include <algorithm>
#include <limits>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include "filum/core/params.hpp"
#include "filum/core/scene.hpp"
#include "filum/haptics/instrument_capsule.hpp"
#include "filum/haptics/instrument_path.hpp"
#include "filum/haptics/instrument_shape.hpp"
#include "filum/haptics/tool.hpp"

namespace filum::haptics {

enum class InstrumentKind { kGrasper, kScissors, kBipolarForceps, kNeedleHolder };
const char* instrumentKindName(InstrumentKind kind);

struct InstrumentSettings {
  std::string name;
  InstrumentKind kind = InstrumentKind::kGrasper;
  InstrumentShape shape;
  InstrumentPath path;
  double close_below = 0.15;
  double holding_force = 2.0;          // N (Grasper)
  double grasp_stiffness = 500.0;      // N/m
  double grasp_damping = -1.0;         // N·s/m (negative: critical, tool.hpp)
  double coagulation_time = 1.0;       // s (BipolarForceps)
  bool require_coagulation = false;    // Scissors: on every body, or on those named
  std::vector<std::string> coagulation_objects;  // node paths (empty with require_coagulation: all)
  double force_limit = std::numeric_limits<double>::infinity();  // N (metrics)
  bool collide = true;
  std::optional<Vec3> trocar;  // the port (m)
  bool device = false;         // driven by a haptic device (InstrumentSet builds it), not a path

  /// From one entry of "instruments" (see above); throws SceneError at the faulty field.
  static InstrumentSettings fromParams(const Params& p);
};

/// A point of a curve body between an instrument's jaws.
struct JawCatch {
  const CurveBody* body = nullptr;
  double abscissa = 0.0;
  double distance = 0.0;  // from the jaws' midline (m)
  double along = 0.0;     // from the hinge along the shaft's axis (m)
};

/// The thread point nearest to the jaws' midline, over the scene's curve bodies, that lay between
/// the jaws at opening `before` and that jaws at opening `now` have closed onto, if any: sampled
/// at 8 abscissas per control point, then refined by golden-section search on the distance to the
/// midline.
std::optional<JawCatch> catchBetweenJaws(const Scene& scene, const InstrumentShape& shape, const InstrumentPose& pose,
                                         double before, double now);

class Instrument {
 public:
  explicit Instrument(InstrumentSettings settings);

  const InstrumentSettings& settings() const { return settings_; }
  const std::string& name() const { return settings_.name; }
  InstrumentKind kind() const { return settings_.kind; }

  /// The pose and opening now (the last setTime) and at the end of the coming step.
  const InstrumentPose& pose() const { return pose_; }
  double opening() const { return opening_; }
  Vec3 tip() const { return settings_.shape.tip(pose_, opening_); }
  /// Where its driver has it at time t (through the trocar's port if it has one), and the jaws'
  /// opening then.
  InstrumentPose poseAt(double t) const;
  double jawAt(double t) const;
  /// Driven by a haptic device: the shaft's orientation `frame`, the buttons that close the jaws,
  /// and how fast they move (1/s).
  /// (`jaw`: the opening at `time` to start from.)
  void driveByDevice(const Eigen::Matrix3d& frame, unsigned buttons, double jaw_speed, double jaw = 1.0,
                     double time = 0.0);
  bool drivenByDevice() const { return drive_.has_value(); }
  /// The stylus sampled at `time` (scene frame): X(t) = X + Ẋ (t − time) from now on; the jaws
  /// close while one of the driving buttons is held, open otherwise. With a trocar the stylus is
  /// the hand on the handle: the hinge is its mirror through the port (the fulcrum effect).
  void setStylus(const Vec3& position, const Vec3& velocity, double time, unsigned buttons);
  /// The hand's position alone (the mouse), and the jaws alone (its keys): closing or opening
  /// from `time` on. A hand-driven instrument's jaws stay as they were until setJaws.
  void setHand(const Vec3& position, const Vec3& velocity, double time);
  void setJaws(bool closing, double time);
  /// Driven: turns the jaws (hinge and frame) by `angle` (rad) about the axis through `centre`
  /// along the unit `axis`, evenly over [time, time + duration] — the wrist's pronation that drives
  /// a held needle along its own curve (centre and axis: the needle's); at once if duration <= 0.
  /// A turn about the same centre and axis still under way adds what it had left to go. The hand's
  /// next stroke (setHand, setStylus) ends the turn where it has got to and moves the jaws on from
  /// there: the hinge's swing is kept as an offset from the hand. (Through a trocar the port turns
  /// the shaft back: InstrumentSet::turnNeedle refuses those.)
  void turnAbout(const Vec3& centre, const Vec3& axis, double angle, double time, double duration);
  /// The driven jaws are closing (false: opening or at rest).
  bool jawsClosing() const { return drive_ && drive_->moving && drive_->closing; }
  /// Moves the instrument to time t (from its driver) and its parts over [t, t + h].
  void setTime(double t, double h);
  /// The opening at the previous setTime (the current one at the first).
  double previousOpening() const { return previous_opening_; }
  /// The jaws close (the opening fell since the previous setTime), open (it rose).
  bool closing() const { return opening_ < previous_opening_; }
  bool opening_up() const { return opening_ > previous_opening_; }
  /// The opening fell to close_below at this step.
  bool reachedClosed() const {
    return previous_opening_ > settings_.close_below && opening_ <= settings_.close_below;
  }
  /// Acted (caught, cut) since the jaws last opened: they act once per closing.
  bool latched() const { return latched_; }
  void latch() { latched_ = true; }

  /// The hold on a thread: the tool state the coupling force fields read.
  const std::shared_ptr<ToolState>& hold() const { return hold_; }
  bool holding() const { return hold_->grasping; }
  /// Holds `point` from now on, caught at `along` from the hinge on the jaws' midline.
  void startHolding(const CurveBody& body, double abscissa, double along);
  /// The jaws have opened wider than when they caught what they hold.
  bool letsGo() const { return (holding() || holds_object_) && opening_ > hold_opening_; }
  /// A rigid object (a needle) is held between the jaws from now on, or no longer.
  void holdObject();
  void releaseObject();
  bool holdsObject() const { return holds_object_; }
  void stopHolding();
  /// The piece of the held thread that lies in the jaws, abscissas [from, to] (InstrumentSet sets
  /// it at every step's start): the jaws let it through — the hold is its contact — and push
  /// everything else, the rest of that thread too (the wraps of an instrument tie lie on the jaws
  /// of the needle holder that holds the short end).
  void setHeldSpan(double from, double to);
  /// Seconds the jaws have held their current point (BipolarForceps coagulation).
  double heldFor() const { return held_for_; }
  void addHeldTime(double h) { held_for_ += h; }

  /// The parts (shaft, jaw +, jaw −) as the collision pipeline's obstacles: created here, owned
  /// by the scene node they are added to.
  std::unique_ptr<InstrumentCapsule> makePart(int index);
  InstrumentCapsule* part(int index) const { return parts_[index]; }
  static constexpr int kParts = 3;
  /// The parts where they are now (drawn, tool-tool contact).
  Capsule partNow(int index) const;

 private:
  /// The point of the jaws' midline where the held point was caught.
  Vec3 anchor(const InstrumentPose& pose) const { return pose.hinge + anchor_along_ * pose.axis(); }
  /// The hold's target and its velocity over the coming step, from the jaws' poses.
  void aimHold();
  InstrumentSettings settings_;
  InstrumentPose pose_, next_;  // now and at the end of the coming step
  double h_ = 1.0;
  double opening_ = 0.0;
  double previous_opening_ = -1.0;  // before the first setTime: none
  double hold_opening_ = 0.0;       // the opening at which the jaws caught what they hold
  bool latched_ = false;
  bool holds_object_ = false;       // a needle
  bool jaws_clear_ = true;          // false from a release until the jaws open past close_below
  bool held_span_ = false;          // holding, and the held piece is known (setHeldSpan)
  /// The jaws push threads (see above).
  bool jawsCollide() const;
  std::shared_ptr<ToolState> hold_ = std::make_shared<ToolState>();
  double anchor_along_ = 0.0, held_for_ = 0.0;
  InstrumentCapsule* parts_[kParts] = {nullptr, nullptr, nullptr};
  struct DeviceDrive {
    Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
    unsigned buttons = 1;
    double jaw_speed = 5.0;
    Vec3 position = Vec3::Zero(), velocity = Vec3::Zero();
    double time = 0.0;
    double jaw = 1.0, jaw_time = 0.0;  // the opening at jaw_time
    bool closing = false;
    bool moving = false;  // the jaws move (a device's always; the mouse's once a key moved them)
    struct Turn {
      Vec3 centre = Vec3::Zero(), axis = Vec3::UnitZ();
      double angle = 0.0, start = 0.0, duration = 1.0;
      /// The fraction of the turn made by time t: (t − start) / duration in [0, 1] (at once when
      /// the duration is not positive).
      double progress(double t) const {
        if (duration <= 0.0) return t >= start ? 1.0 : 0.0;
        return std::clamp((t - start) / duration, 0.0, 1.0);
      }
    };
    std::optional<Turn> turn;  // applied after the hand's position and frame (turnAbout)
    Vec3 hand_offset = Vec3::Zero();  // the hinge's swing by the turns made so far, off the hand
  };
  /// Makes the turn under way part of the drive at `time` (frame and hand offset), and ends it.
  void bakeTurn(double time);
  /// A drive's pose at time t before the trocar's port is applied.
  InstrumentPose drivenPose(double t) const;
  std::optional<DeviceDrive> drive_;
};

}  // namespace filum::haptics
