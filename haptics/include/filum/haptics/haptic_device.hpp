// HapticDevice: a stylus the servo loop reads and pushes, whatever it is (a Phantom through
// OpenHaptics, a script, a simulated hand and stylus, the mouse).
//
// Everything here is in the device's frame and SI units (m, m/s, N, rad, N·m); DeviceFrame maps it
// into the scene. Besides the stylus's position, a device reports its roll: the turn of the stylus
// about its own axis (a Phantom's last gimbal joint), and a device with six output axes renders a
// torque about that axis (the hand turning a catheter's hub feels the wire's twist). read() and write() are called only from the servo tick, one read then one write per
// tick; start() runs the ticks at the servo rate on the device's own servo thread (a Phantom's
// is the OpenHaptics scheduler; the others use PeriodicThread), stop() ends them and leaves the
// force at zero. runTick() runs one tick on the caller's thread instead: the lockstep mode of
// headless runs, where the servo time advances by exactly one period per tick so that a run is
// deterministic.
#pragma once

#include <functional>
#include <string>

#include "filum/core/types.hpp"
#include "filum/haptics/device_limits.hpp"

namespace filum::haptics {

/// The stylus as one tick reads it (device frame).
struct DeviceState {
  Vec3 position = Vec3::Zero();  // m
  Vec3 velocity = Vec3::Zero();  // m/s
  unsigned buttons = 0;          // bit k: button k + 1 held
  double roll = 0.0;             // rad, the stylus turned about its own axis (right-handed)
};

/// One servo tick: t is the servo time (s since start; in lockstep k·T exactly). Returns false
/// to stop the loop.
using ServoTick = std::function<bool(double t)>;

class HapticDevice {
 public:
  virtual ~HapticDevice() = default;
  /// "OpenHaptics 'Default Device'", "ScriptedDevice", ...
  virtual std::string name() const = 0;
  virtual const DeviceLimits& limits() const = 0;
  /// Whether the device can run in lockstep (runTick): scripted and simulated devices can, a
  /// physical device cannot (its time is the wall clock).
  virtual bool canRunLockstep() const = 0;

  /// Reads the stylus at servo time t (inside a tick).
  virtual DeviceState read(double t) = 0;
  /// Sends a force (N, device frame), already made safe by ForceSafety (inside a tick).
  virtual void write(const Vec3& force) = 0;
  /// Sends a torque about the stylus's own axis (N·m, right-handed like the roll), already made
  /// safe by ForceSafety (inside a tick). A device that renders no torque (limits().peak_torque
  /// = 0: a Touch, a Premium 1.5 without the 6-DOF option) ignores it.
  virtual void writeTorque(double torque) { (void)torque; }

  /// Runs `tick` at `rate` (Hz) on the servo thread until it returns false or stop() is called.
  /// Throws std::runtime_error when the thread or the device's scheduler cannot start.
  virtual void start(ServoTick tick, double rate) = 0;
  /// Stops the ticks (joins the servo thread) and leaves the force at zero. Idempotent.
  virtual void stop() = 0;
  /// What start() could not have (real-time priority refused, ...), or "".
  virtual std::string schedulingNote() const { return ""; }
};

}  // namespace filum::haptics
