// HubDevice: a haptic device on an instrument's hub — the scene's "navigation" block's "device".
// The stylus pushed along the introducer's axis feeds a catheter or guidewire in, turned about its
// own axis rolls it; the force along the axis and the torque about it that the hand needs come
// back to the device: the force through the stylus's three axes, the torque through the gimbal's
// last joint on a device that renders one (DeviceLimits::peak_torque; a Touch does not).
//
//   "navigation": {"instruments": ["guidewire"], ...,
//     "device": {"device": {"type": "ScriptedDevice", "model": "Touch", "waypoints": [...]},
//                "frame": {...}, "limits": {...}, "rate": 1000, "mode": ..., "watchdog", "fade",
//                                                    (as a "haptics" block: haptic_session.hpp)
//                "instrument": "guidewire",          default: the block's first instrument
//                "button": 1,                        the grip (1 to 16)
//                "roll_scale": 1}}                   hub roll per stylus roll (−1: the other sense)
//
// The grip is a clutch, as a hand feeds a wire through a haemostatic valve in strokes: while the
// button is held the hub follows the stylus,
//     d(t) = d_g + (x(t) − x_g)·a₀,   ψ(t) = ψ_g + r (θ(t) − θ_g),
// d the hub's insertion along the introducer's axis a₀ (HubControl::insertion), ψ its roll, x the
// stylus in the scene frame (DeviceFrame), θ the stylus's roll, r the roll scale, and x_g, θ_g,
// d_g, ψ_g stylus and hub when the button went down; released, the hub stays where it is and the
// hand goes back freely. Before each step the hub's target is set to d and moves on at the
// stylus's speed along a₀ over the step (HubControl::steer: X(t) = X + V (t − t_sample), as the
// tools' fields see the stylus), and its roll reaches ψ at the step's end (HubControl::rollTo).
//
// What the hand feels while it grips (nothing otherwise): the reaction to its push along the axis,
//     F = −(f·a₀) a₀,   f the hub constraint's force on the instrument (HubControl::force),
// and the reaction to its turn,
//     τ = −r (t·a₀),    t the RodEndFrame's torque on the instrument (HubControl::torque);
// the introducer takes f's part across a₀. After each step they become the servo's model (F0 = F,
// τ0 = τ, K = D = 0), held until the next one: the hub is driven in position, so the instrument's
// resistance comes back sampled at the step rate (a zero-order hold), through ForceSafety (the
// force: slew, peak and continuous limits; the torque: slew and peak). A wire jammed against a
// wall is stiff: it is felt only as stiff as the slew rate lets the force change within a step,
// not rendered as a passive spring.
// A stylus that sends nothing for longer than the watchdog leaves the hub where it is (the grip
// ends: a button still held when samples come back is a new grip). A hub whose constraint lets go
// (released, cut) is driven no more, and the summary says when (lost()).
#pragma once

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "filum/core/scene.hpp"
#include "filum/haptics/haptic_session.hpp"
#include "filum/haptics/hub_control.hpp"

namespace filum::haptics {

class HubDevice {
 public:
  /// The device of document["navigation"]["device"] on its instrument's hub, nullptr when the
  /// block has none. Throws SceneError at the faulty JSON path (an unknown instrument, one whose
  /// s = 0 no point constraint holds, a bad button or roll scale, the device block's errors, a
  /// scene with a "haptics" block too: one device a run).
  static std::unique_ptr<HubDevice> fromScene(const nlohmann::json& document, const std::string& source, Scene& scene,
                                              double duration);

  /// Starts the servo loop (thread mode) and the Ctrl-C handler.
  void start() { session_->start(); }
  /// Before a step: the ticks due (lockstep), the grip, the hub driven to the stylus.
  void beforeStep(Scene& scene);
  /// Why the hub is no longer driven ("" while it is).
  const std::string& lost() const { return lost_; }
  /// After a step: the force and torque on the hand published to the servo loop.
  void afterStep(const Scene& scene);
  /// Forces off. Idempotent.
  void finish() { session_->finish(); }
  bool threaded() const { return session_->threaded(); }
  bool interrupted() const { return session_->interrupted(); }

  /// haptics.csv (HapticSession::writeCsv).
  void writeCsv(const std::string& path) const { session_->writeCsv(path); }
  /// The servo's line, then the hub's: strokes, inserted length and roll by the hand, the largest
  /// force and torque on it.
  std::string summary() const;

  const HubControl& hub() const { return *hub_; }
  bool gripping() const { return gripping_; }
  int strokes() const { return strokes_; }
  /// This step's force (N, scene frame) and torque (N·m, about the stylus's axis) on the hand.
  const Vec3& handForce() const { return hand_force_; }
  double handTorque() const { return hand_torque_; }
  double largestForce() const { return largest_force_; }
  double largestTorque() const { return largest_torque_; }
  HapticSession& session() { return *session_; }

 private:
  HubDevice() = default;
  /// beforeStep's work; throws SceneError when the hub's constraint holds nothing any more.
  void drive(Scene& scene);

  std::unique_ptr<HapticSession> session_;
  std::unique_ptr<HubControl> hub_;
  unsigned button_mask_ = 1;
  double roll_scale_ = 1.0;
  // The grip.
  bool gripping_ = false;
  int strokes_ = 0;
  Vec3 grip_stylus_ = Vec3::Zero();
  double grip_roll_ = 0.0, grip_insertion_ = 0.0, grip_hub_roll_ = 0.0;
  double last_sample_time_ = 0.0;  // s, of the newest stylus sample
  std::string lost_;               // why the hub is driven no more
  // What the hand feels.
  Vec3 hand_force_ = Vec3::Zero();
  double hand_torque_ = 0.0, largest_force_ = 0.0, largest_torque_ = 0.0;
};

}  // namespace filum::haptics
