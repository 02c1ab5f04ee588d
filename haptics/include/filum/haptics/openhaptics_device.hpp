// OpenHapticsDevice: the Phantom family (3D Systems Touch, Touch X, Omni, Premium) through the
// OpenHaptics HD API. Built only where the SDK is found (CMake option FILUM_WITH_OPENHAPTICS;
// the SDK is not a Debian package), and tested in CI against the fake HD library of
// tests/haptics/fake_hd, which checks the calls, units and frames without hardware.
//
// The HD API's rules, which this class follows:
//   - hdInitDevice(name) opens the device (HD_DEFAULT_DEVICE: the default one); hdGetError after
//     every call that may fail; hdEnable(HD_FORCE_OUTPUT) before any force;
//   - state (HD_CURRENT_POSITION in mm, HD_CURRENT_VELOCITY in mm/s, HD_CURRENT_BUTTONS) is read
//     and HD_CURRENT_FORCE (N) is set only between hdBeginFrame and hdEndFrame, inside a callback
//     of the HD scheduler (hdScheduleAsynchronous; hdStartScheduler runs it at hdSetSchedulerRate);
//   - the stylus's roll is the last gimbal angle (HD_CURRENT_GIMBAL_ANGLES[2], rad); a torque
//     about it is set as HD_CURRENT_GIMBAL_TORQUE (mN·m) and only on a device with six output
//     axes (HD_OUTPUT_DOF; its HD_NOMINAL_MAX_TORQUE_FORCE, mN·m, is the peak torque);
//   - the device's frame: x to the right, y up, z toward the user, origin near the workspace
//     centre (DeviceFrame maps it into the scene).
// The limits come from the device (HD_NOMINAL_MAX_FORCE, HD_NOMINAL_MAX_CONTINUOUS_FORCE,
// HD_NOMINAL_MAX_STIFFNESS in N/mm, HD_USABLE_WORKSPACE_DIMENSIONS in mm); damping and stylus
// mass, which it does not report, from the preset.
//
// The inline namespace keeps the SDK build and the test build against the fake library apart
// (both may be in one program: the library's and the test's).
#pragma once

#include <memory>
#include <string>

#include "filum/haptics/haptic_device.hpp"

#ifndef FILUM_OPENHAPTICS_VARIANT
#define FILUM_OPENHAPTICS_VARIANT sdk
#endif

namespace filum::haptics {
inline namespace FILUM_OPENHAPTICS_VARIANT {

class OpenHapticsDevice final : public HapticDevice {
 public:
  /// Opens the device named in the Touch Setup utility ("" for the default device); `preset`
  /// gives the damping and stylus mass. Throws std::runtime_error with the HD error's text.
  OpenHapticsDevice(const std::string& device_name, const DeviceLimits& preset);
  ~OpenHapticsDevice() override;

  std::string name() const override { return "OpenHaptics '" + (device_name_.empty() ? "default" : device_name_) + "'"; }
  const DeviceLimits& limits() const override { return limits_; }
  bool canRunLockstep() const override { return false; }
  DeviceState read(double t) override;
  void write(const Vec3& force) override;
  /// On the gimbal's last joint (HD_CURRENT_GIMBAL_TORQUE, mN·m) of a device with six output axes.
  void writeTorque(double torque) override;
  void start(ServoTick tick, double rate) override;
  void stop() override;

 private:
  struct Scheduler;  // the HD scheduler's callback and handle
  /// Throws std::runtime_error naming `call` if the HD error stack is not empty.
  void check(const char* call) const;
  std::string device_name_;
  DeviceLimits limits_;
  unsigned handle_ = 0;  // HHD
  bool in_frame_ = false;
  bool force_output_ = false;  // HD_FORCE_OUTPUT enabled (stop() disables it once)
  std::unique_ptr<Scheduler> scheduler_;
};

}  // namespace FILUM_OPENHAPTICS_VARIANT
}  // namespace filum::haptics
