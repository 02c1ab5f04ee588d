// The fake HD library (see include/HD/hd.h): the device's state and the scheduler's callbacks
// in one process-wide object, driven by the test through fake_hd_control.h.
#include <HD/hd.h>

#include <cstring>
#include <vector>

#include "fake_hd_control.h"

namespace {

struct Callback {
  HDSchedulerCallback function;
  void* data;
  bool active;
};

struct Device {
  fake_hd::Record record;
  double position[3] = {0, 0, 0}, velocity[3] = {0, 0, 0};
  int buttons = 0;
  double gimbal[3] = {0, 0, 0};
  int output_axes = 3;
  double max_torque = 0.0;  // mN·m
  double max_force = 3.3, continuous_force = 0.88, stiffness = 1.02;  // a Touch (N, N, N/mm)
  double box[6] = {-80, -60, -35, 80, 60, 35};                         // mm
  bool in_frame = false;
  bool fail_init = false;
  std::vector<HDErrorInfo> errors;
  std::vector<Callback> callbacks;
};

Device& device() {
  static Device d;
  return d;
}

void raise(HDerror code, const char* what) {
  device().errors.push_back(HDErrorInfo{code, 0, 0});
  device().record.misuse.push_back(what);
}

void requireFrame(const char* call) {
  if (!device().in_frame) raise(HD_INVALID_OPERATION, (std::string(call) + " outside a frame").c_str());
}

}  // namespace

namespace fake_hd {

void reset() { device() = Device{}; }
const Record& record() { return device().record; }

void setStylus(double x, double y, double z, double vx, double vy, double vz, int buttons) {
  Device& d = device();
  d.position[0] = x, d.position[1] = y, d.position[2] = z;
  d.velocity[0] = vx, d.velocity[1] = vy, d.velocity[2] = vz;
  d.buttons = buttons;
}

void setGimbal(double a, double b, double roll) {
  Device& d = device();
  d.gimbal[0] = a, d.gimbal[1] = b, d.gimbal[2] = roll;
}

void setOutputAxes(int axes, double max_torque_mnm) {
  device().output_axes = axes;
  device().max_torque = max_torque_mnm;
}

void setNominal(double max_force, double continuous_force, double stiffness, const double box[6]) {
  Device& d = device();
  d.max_force = max_force, d.continuous_force = continuous_force, d.stiffness = stiffness;
  std::memcpy(d.box, box, sizeof d.box);
}

void failNextInit() { device().fail_init = true; }

int runSchedulerTick() {
  Device& d = device();
  if (!d.record.scheduler_running) return 0;
  int continuing = 0;
  for (Callback& c : d.callbacks) {
    if (!c.active) continue;
    c.active = c.function(c.data) == HD_CALLBACK_CONTINUE;
    continuing += c.active;
  }
  return continuing;
}

}  // namespace fake_hd

extern "C" {

HHD hdInitDevice(HDstring name) {
  Device& d = device();
  if (d.fail_init) {
    d.fail_init = false;
    d.errors.push_back(HDErrorInfo{HD_DEVICE_FAULT, 42, 0});
    return HD_INVALID_HANDLE;
  }
  d.record.initialized = true;
  d.record.device_name = name ? name : "<default>";
  return 1;
}

void hdDisableDevice(HHD) { device().record.initialized = false; }

void hdBeginFrame(HHD) {
  Device& d = device();
  if (d.in_frame) raise(HD_ILLEGAL_BEGIN, "hdBeginFrame inside a frame");
  d.in_frame = true;
}

void hdEndFrame(HHD) {
  Device& d = device();
  if (!d.in_frame) raise(HD_INVALID_OPERATION, "hdEndFrame without hdBeginFrame");
  d.in_frame = false;
  ++d.record.frames;
}

HDErrorInfo hdGetError(void) {
  Device& d = device();
  if (d.errors.empty()) return HDErrorInfo{HD_SUCCESS, 0, 0};
  const HDErrorInfo e = d.errors.back();
  d.errors.pop_back();
  return e;
}

HDstring hdGetErrorString(HDerror code) {
  switch (code) {
    case HD_DEVICE_FAULT: return "device fault (no such device)";
    case HD_INVALID_OPERATION: return "invalid operation";
    case HD_ILLEGAL_BEGIN: return "illegal begin";
    default: return "unknown error";
  }
}

void hdEnable(HDenum cap) {
  if (cap == HD_FORCE_OUTPUT) device().record.force_output = true;
}

void hdDisable(HDenum cap) {
  if (cap == HD_FORCE_OUTPUT) device().record.force_output = false;
}

void hdGetDoublev(HDenum pname, HDdouble* out) {
  Device& d = device();
  switch (pname) {
    case HD_CURRENT_POSITION: requireFrame("hdGetDoublev(HD_CURRENT_POSITION)"); std::memcpy(out, d.position, 3 * sizeof(double)); break;
    case HD_CURRENT_VELOCITY: requireFrame("hdGetDoublev(HD_CURRENT_VELOCITY)"); std::memcpy(out, d.velocity, 3 * sizeof(double)); break;
    case HD_CURRENT_GIMBAL_ANGLES: requireFrame("hdGetDoublev(HD_CURRENT_GIMBAL_ANGLES)"); std::memcpy(out, d.gimbal, 3 * sizeof(double)); break;
    case HD_NOMINAL_MAX_TORQUE_FORCE: *out = d.max_torque; break;
    case HD_NOMINAL_MAX_FORCE: *out = d.max_force; break;
    case HD_NOMINAL_MAX_CONTINUOUS_FORCE: *out = d.continuous_force; break;
    case HD_NOMINAL_MAX_STIFFNESS: *out = d.stiffness; break;
    case HD_USABLE_WORKSPACE_DIMENSIONS: std::memcpy(out, d.box, 6 * sizeof(double)); break;
    default: raise(HD_INVALID_OPERATION, "hdGetDoublev of an unknown parameter");
  }
}

void hdGetIntegerv(HDenum pname, HDint* out) {
  if (pname == HD_OUTPUT_DOF) {
    *out = device().output_axes;
    return;
  }
  if (pname != HD_CURRENT_BUTTONS) return raise(HD_INVALID_OPERATION, "hdGetIntegerv of an unknown parameter");
  requireFrame("hdGetIntegerv(HD_CURRENT_BUTTONS)");
  *out = device().buttons;
}

void hdSetDoublev(HDenum pname, const HDdouble* in) {
  Device& d = device();
  if (pname == HD_CURRENT_GIMBAL_TORQUE) {
    requireFrame("hdSetDoublev(HD_CURRENT_GIMBAL_TORQUE)");
    if (d.output_axes < 6) raise(HD_INVALID_OPERATION, "a gimbal torque set on a device without torque output");
    d.record.gimbal_torques.push_back({in[0], in[1], in[2]});
    return;
  }
  if (pname != HD_CURRENT_FORCE) return raise(HD_INVALID_OPERATION, "hdSetDoublev of an unknown parameter");
  requireFrame("hdSetDoublev(HD_CURRENT_FORCE)");
  if (!d.record.force_output) raise(HD_INVALID_OPERATION, "a force set with HD_FORCE_OUTPUT disabled");
  d.record.forces.push_back({in[0], in[1], in[2]});
}

void hdStartScheduler(void) { device().record.scheduler_running = true; }
void hdStopScheduler(void) { device().record.scheduler_running = false; }
void hdSetSchedulerRate(HDulong rate) { device().record.scheduler_rate = rate; }

HDSchedulerHandle hdScheduleAsynchronous(HDSchedulerCallback f, void* data, HDushort) {
  device().callbacks.push_back(Callback{f, data, true});
  return device().callbacks.size();
}

void hdUnschedule(HDSchedulerHandle handle) {
  if (handle >= 1 && handle <= device().callbacks.size()) device().callbacks[handle - 1].active = false;
}

}  // extern "C"
