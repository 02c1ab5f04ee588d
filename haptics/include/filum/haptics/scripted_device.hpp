// ScriptedDevice: a stylus that follows a StylusScript and ignores the forces sent to it (it
// records the last one): for headless runs, demos and tests. Runs in lockstep (deterministic)
// or on a PeriodicThread.
#pragma once

#include "filum/haptics/haptic_device.hpp"
#include "filum/haptics/periodic_thread.hpp"
#include "filum/haptics/stylus_script.hpp"

namespace filum::haptics {

class ScriptedDevice final : public HapticDevice {
 public:
  ScriptedDevice(StylusScript script, DeviceLimits limits) : script_(std::move(script)), limits_(limits) {}
  ~ScriptedDevice() override { stop(); }

  std::string name() const override { return "ScriptedDevice"; }
  const DeviceLimits& limits() const override { return limits_; }
  bool canRunLockstep() const override { return true; }
  DeviceState read(double t) override {
    return DeviceState{script_.position(t), script_.velocity(t), script_.buttons(t), script_.roll(t)};
  }
  void write(const Vec3& force) override { last_force_ = force; }
  void writeTorque(double torque) override { last_torque_ = torque; }
  void start(ServoTick tick, double rate) override { thread_.start(std::move(tick), rate); }
  void stop() override {
    thread_.stop();
    last_force_.setZero();
    last_torque_ = 0.0;
  }
  std::string schedulingNote() const override { return thread_.schedulingNote(); }

  const Vec3& lastForce() const { return last_force_; }
  double lastTorque() const { return last_torque_; }
  const StylusScript& script() const { return script_; }

 private:
  StylusScript script_;
  DeviceLimits limits_;
  Vec3 last_force_ = Vec3::Zero();
  double last_torque_ = 0.0;
  PeriodicThread thread_;
};

}  // namespace filum::haptics
