// SimulatedDevice: a device and the hand that holds it, simulated, so that the closed loop of a
// haptic interaction — and its stability — can be tested without hardware.
//
// The stylus is a mass m with the mechanism's viscous damping b (DeviceLimits: stylus_mass,
// damping); the hand is a spring–damper (k_h, c_h) pulling it toward a scripted target X(t):
//   m ẍ = F + k_h (X(t) − x) − c_h ẋ − b ẋ,
// F the force the servo sent, held constant over the servo period (zero-order hold, as a real
// device's amplifier holds it). read(t) integrates from the previous read to t in sub-steps of at
// most T/20 (semi-implicit Euler with the damping implicit: stable for any b, c_h; the plant is
// resolved 20 times finer than the servo samples it), and reports the velocity as a real device
// does, by backward difference of the sampled positions, (x_k − x_{k−1}) / (t_k − t_{k−1}) —
// the estimate Colgate's passivity condition assumes. k_h = 0 lets the stylus go: a free
// stylus against the virtual environment, the test of passivity. The stylus's roll is the
// script's, as the hand turns it: the torque sent is recorded (lastTorque), not integrated.
#pragma once

#include "filum/haptics/haptic_device.hpp"
#include "filum/haptics/periodic_thread.hpp"
#include "filum/haptics/stylus_script.hpp"

namespace filum::haptics {

struct HandModel {
  double stiffness = 200.0;  // k_h, N/m: a relaxed grip (Hajian & Howe 1997 report 100–600 N/m)
  double damping = 2.0;      // c_h, N·s/m
};

class SimulatedDevice final : public HapticDevice {
 public:
  /// The stylus starts at rest at the target's first position.
  SimulatedDevice(StylusScript target, DeviceLimits limits, HandModel hand);
  ~SimulatedDevice() override { stop(); }

  std::string name() const override { return "SimulatedDevice"; }
  const DeviceLimits& limits() const override { return limits_; }
  bool canRunLockstep() const override { return true; }
  DeviceState read(double t) override;
  void write(const Vec3& force) override { force_ = force; }
  void writeTorque(double torque) override { torque_ = torque; }
  double lastTorque() const { return torque_; }
  void start(ServoTick tick, double rate) override { thread_.start(std::move(tick), rate); }
  void stop() override {
    thread_.stop();
    force_.setZero();
  }
  std::string schedulingNote() const override { return thread_.schedulingNote(); }

  /// Puts the stylus at x with velocity v (tests: an initial displacement).
  void place(const Vec3& x, const Vec3& v);
  /// The stylus's true state (not the backward-difference estimate read() reports).
  const Vec3& truePosition() const { return x_; }
  const Vec3& trueVelocity() const { return v_; }
  /// Work done on the stylus by the forces sent, ∫ F·ẋ dt (J), exact for the sub-steps.
  double workByDevice() const { return work_; }

 private:
  StylusScript target_;
  DeviceLimits limits_;
  HandModel hand_;
  Vec3 x_ = Vec3::Zero(), v_ = Vec3::Zero();
  Vec3 force_ = Vec3::Zero();
  double torque_ = 0.0;
  Vec3 last_read_position_ = Vec3::Zero();
  double time_ = 0.0, last_read_time_ = 0.0;
  double work_ = 0.0;
  bool read_once_ = false;
  PeriodicThread thread_;
};

}  // namespace filum::haptics
