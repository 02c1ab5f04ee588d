// Compiled only with the OpenHaptics SDK (FILUM_WITH_OPENHAPTICS) or, for the tests, against
// the fake HD library of tests/haptics/fake_hd (see the header).
#include "filum/haptics/openhaptics_device.hpp"

#include <HD/hd.h>

#include <chrono>
#include <stdexcept>

namespace filum::haptics {
inline namespace FILUM_OPENHAPTICS_VARIANT {

namespace {

constexpr double kMillimetre = 1e-3;  // the HD API's lengths are in mm, forces in N
constexpr double kMilli = 1e-3;       // and its gimbal torques in mN·m

}  // namespace

struct OpenHapticsDevice::Scheduler {
  OpenHapticsDevice* device = nullptr;
  ServoTick tick;
  HDSchedulerHandle callback = HD_INVALID_HANDLE;
  std::chrono::steady_clock::time_point start;
  bool running = false;

  /// The servo tick inside one HD frame; HD_CALLBACK_DONE ends the callback.
  static HDCallbackCode HDCALLBACK run(void* data) {
    auto& self = *static_cast<Scheduler*>(data);
    OpenHapticsDevice& device = *self.device;
    hdBeginFrame(device.handle_);
    device.in_frame_ = true;
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - self.start).count();
    bool go = self.tick(t);
    device.in_frame_ = false;
    hdEndFrame(device.handle_);
    if (HD_DEVICE_ERROR(hdGetError())) go = false;  // a device fault (overheating, ...): stop; stop() zeroes
    return go ? HD_CALLBACK_CONTINUE : HD_CALLBACK_DONE;
  }
};

OpenHapticsDevice::OpenHapticsDevice(const std::string& device_name, const DeviceLimits& preset)
    : device_name_(device_name), limits_(preset), scheduler_(std::make_unique<Scheduler>()) {
  handle_ = hdInitDevice(device_name.empty() ? HD_DEFAULT_DEVICE : device_name.c_str());
  check("hdInitDevice");
  HDdouble value = 0.0;
  hdGetDoublev(HD_NOMINAL_MAX_FORCE, &value);
  if (value > 0.0) limits_.peak_force = value;
  hdGetDoublev(HD_NOMINAL_MAX_CONTINUOUS_FORCE, &value);
  if (value > 0.0) limits_.continuous_force = value;
  hdGetDoublev(HD_NOMINAL_MAX_STIFFNESS, &value);
  if (value > 0.0) limits_.max_stiffness = value / kMillimetre;  // N/mm → N/m
  HDdouble box[6] = {0, 0, 0, 0, 0, 0};
  hdGetDoublev(HD_USABLE_WORKSPACE_DIMENSIONS, box);
  if (box[3] > box[0] && box[4] > box[1] && box[5] > box[2]) {
    limits_.workspace_min = Vec3(box[0], box[1], box[2]) * kMillimetre;
    limits_.workspace_max = Vec3(box[3], box[4], box[5]) * kMillimetre;
  }
  check("hdGetDoublev (nominal limits)");
  // Torque about the stylus's axis only on a device with six output axes (a Premium 6-DOF); its
  // nominal largest gimbal torque in mN·m, as HD_CURRENT_GIMBAL_TORQUE takes it.
  HDint output_axes = 3;
  hdGetIntegerv(HD_OUTPUT_DOF, &output_axes);
  check("hdGetIntegerv(HD_OUTPUT_DOF)");
  limits_.peak_torque = 0.0;
  if (output_axes >= 6) {
    value = 0.0;
    hdGetDoublev(HD_NOMINAL_MAX_TORQUE_FORCE, &value);
    check("hdGetDoublev(HD_NOMINAL_MAX_TORQUE_FORCE)");
    if (value > 0.0) limits_.peak_torque = value * kMilli;
  }
  hdEnable(HD_FORCE_OUTPUT);
  check("hdEnable(HD_FORCE_OUTPUT)");
  force_output_ = true;
}

OpenHapticsDevice::~OpenHapticsDevice() {
  stop();
  hdDisableDevice(handle_);
}

void OpenHapticsDevice::check(const char* call) const {
  const HDErrorInfo error = hdGetError();
  if (HD_DEVICE_ERROR(error))
    throw std::runtime_error(std::string("OpenHaptics: ") + call + " failed: " + hdGetErrorString(error.errorCode) +
                             " (HD error " + std::to_string(error.errorCode) + ", device error " +
                             std::to_string(error.internalErrorCode) + ")");
}

DeviceState OpenHapticsDevice::read(double) {
  DeviceState state;
  HDdouble p[3] = {0, 0, 0}, v[3] = {0, 0, 0};
  HDint buttons = 0;
  hdGetDoublev(HD_CURRENT_POSITION, p);
  hdGetDoublev(HD_CURRENT_VELOCITY, v);
  hdGetIntegerv(HD_CURRENT_BUTTONS, &buttons);
  HDdouble gimbal[3] = {0, 0, 0};
  hdGetDoublev(HD_CURRENT_GIMBAL_ANGLES, gimbal);  // rad; the last joint turns the stylus about its axis
  state.roll = gimbal[2];
  state.position = Vec3(p[0], p[1], p[2]) * kMillimetre;
  state.velocity = Vec3(v[0], v[1], v[2]) * kMillimetre;
  state.buttons = static_cast<unsigned>(buttons);
  return state;
}

void OpenHapticsDevice::write(const Vec3& force) {
  if (!in_frame_) return;  // outside a frame the HD API refuses state calls; stop() zeroes the force
  const HDdouble f[3] = {force.x(), force.y(), force.z()};
  hdSetDoublev(HD_CURRENT_FORCE, f);
}

void OpenHapticsDevice::writeTorque(double torque) {
  if (!in_frame_ || !(limits_.peak_torque > 0.0)) return;  // a 3-DOF gimbal has no motor
  const HDdouble gimbal[3] = {0.0, 0.0, torque / kMilli};   // N·m → mN·m, on the last joint
  hdSetDoublev(HD_CURRENT_GIMBAL_TORQUE, gimbal);
}

void OpenHapticsDevice::start(ServoTick tick, double rate) {
  if (scheduler_->running) throw std::logic_error("OpenHapticsDevice::start: already running");
  scheduler_->device = this;
  scheduler_->tick = std::move(tick);
  scheduler_->start = std::chrono::steady_clock::now();
  hdEnable(HD_FORCE_OUTPUT);  // (stop() disables it)
  force_output_ = true;
  hdSetSchedulerRate(static_cast<HDulong>(rate));
  check("hdSetSchedulerRate");
  scheduler_->callback = hdScheduleAsynchronous(&Scheduler::run, scheduler_.get(), HD_MAX_SCHEDULER_PRIORITY);
  check("hdScheduleAsynchronous");
  hdStartScheduler();
  check("hdStartScheduler");
  scheduler_->running = true;
}

void OpenHapticsDevice::stop() {
  if (scheduler_->running) {
    hdStopScheduler();
    hdUnschedule(scheduler_->callback);
    scheduler_->running = false;
  }
  // Forces off: one last frame with zero force, then force output disabled (once).
  if (force_output_) {
    hdBeginFrame(handle_);
    in_frame_ = true;
    write(Vec3::Zero());
    writeTorque(0.0);
    in_frame_ = false;
    hdEndFrame(handle_);
    hdDisable(HD_FORCE_OUTPUT);
    force_output_ = false;
  }
  hdGetError();  // clears the stack: nothing more can be done about a fault while stopping
}

}  // namespace FILUM_OPENHAPTICS_VARIANT
}  // namespace filum::haptics
