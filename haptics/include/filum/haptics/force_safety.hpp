// ForceSafety: the last stage before every device write (docs/architecture.md, "One step": nothing
// non-finite reaches a file or a device). In order, for the commanded force F at servo time t:
//   1. a non-finite component makes the whole force zero at once, with no slew (and is counted);
//   2. watchdog: when the simulation has not published a model for `watchdog` seconds (50 ms),
//      a gain g falls linearly to 0 over `fade` seconds, and rises back the same way once models
//      arrive again: F ← g F, so the hand is never left against a frozen spring nor jolted;
//   3. slew rate: |F_k − F_{k−1}| ≤ slew_rate · T (the force moves toward the command);
//   4. peak and continuous limits: |F| ≤ peak_force, and the RMS of |F| over the window W stays
//      ≤ continuous_force. The RMS is an exponential mean of |F|² with time constant W,
//        m_k = m_{k−1} + α (|F_k|² − m_{k−1}),  α = T / W,
//      so |F_k| is limited to sqrt(m_{k−1} + (c² − m_{k−1}) / α): short bursts up to the peak
//      pass, a held force settles at the continuous limit (the motors' heating, I²t). The limits
//      come last: they may cut a force faster than the slew rate, never let one through.
// Steps 1, 2 and 4 scale the force's magnitude and keep its direction.
// A torque about the stylus's axis (applyTorque, after apply at the same tick): 0 on a device that
// renders none (peak_torque 0); else a non-finite one is 0 at once (counted apart), the force's
// watchdog gain scales it, it is clamped to ±peak_torque and slewed over the force's rise time
// (peak_torque · slew_rate / peak_force per second). No continuous limit: the makers publish
// none for the gimbal's motor that this reads (HD_NOMINAL_MAX_TORQUE_FORCE is a peak).
#pragma once

#include "filum/core/types.hpp"
#include "filum/haptics/device_limits.hpp"

namespace filum::haptics {

struct SafetySettings {
  double watchdog = 0.05;  // s without a new model before the force fades
  double fade = 0.05;      // s from full force to zero
};

class ForceSafety {
 public:
  ForceSafety(const DeviceLimits& limits, SafetySettings settings, double period);

  /// The force to send for the commanded one at servo time t, `fresh` when a new model arrived
  /// at this tick.
  Vec3 apply(const Vec3& commanded, double t, bool fresh);
  /// The torque to send for the commanded one (N·m), at the tick apply() has just run.
  double applyTorque(double commanded);

  long nonFiniteCount() const { return non_finite_; }
  long nonFiniteTorqueCount() const { return non_finite_torques_; }
  /// The watchdog's gain g ∈ [0, 1] at the last tick.
  double watchdogGain() const { return gain_; }
  /// Whether the watchdog held the force below the command at the last tick.
  bool watchdogActive() const { return gain_ < 1.0; }
  const Vec3& lastSent() const { return last_; }

 private:
  DeviceLimits limits_;
  SafetySettings settings_;
  double period_;
  double alpha_;               // T / W of the continuous limit's mean
  double mean_square_ = 0.0;   // m_k (N²)
  double last_model_time_ = 0.0;
  double gain_ = 1.0;
  Vec3 last_ = Vec3::Zero();
  long non_finite_ = 0;
  long non_finite_torques_ = 0;
  double last_torque_ = 0.0;
};

}  // namespace filum::haptics
