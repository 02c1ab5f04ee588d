// ServoLoop: the 1 kHz loop between a device and the simulation (docs/haptics.md, "What runs").
//
// One tick, at servo time t (the device's servo thread, or the caller's in lockstep):
//   1. read the stylus (device frame) and map it into the scene (DeviceFrame);
//   2. take the newest local model the simulation published, if one arrived (TripleBuffer: the
//      tick never waits for a step);
//   3. F_scene = F0 + K (x − x0) + D (v − v0) (LocalLinearModel), F_device = DeviceFrame's map;
//   4. ForceSafety: non-finite → 0, watchdog fade, slew rate, peak and continuous limits;
//      The model's torque about the stylus's axis goes the same way (force_scale, ForceSafety's
//      applyTorque) to writeTorque;
//   5. write F_device; publish the sample (stylus, buttons, forces, period) to the simulation
//      and append it to the log (preallocated: a full log drops samples and counts them).
// The simulation thread calls publish() after each step and latestSample() before the next.
// A Ctrl-C (interrupt.hpp) makes the next tick send zero and stop the loop.
#pragma once

#include <atomic>
#include <cstddef>
#include <string>
#include <vector>

#include "filum/haptics/device_frame.hpp"
#include "filum/haptics/force_safety.hpp"
#include "filum/haptics/haptic_device.hpp"
#include "filum/haptics/local_linear_model.hpp"
#include "filum/haptics/triple_buffer.hpp"

namespace filum::haptics {

/// What one tick saw and did.
struct ServoSample {
  double time = 0.0;             // servo time (s)
  double period = 0.0;           // since the previous tick (s)
  Vec3 position = Vec3::Zero();  // stylus, scene frame (m)
  Vec3 velocity = Vec3::Zero();  // stylus, scene frame (m/s)
  unsigned buttons = 0;
  double roll = 0.0;              // stylus roll about its own axis (rad)
  Vec3 commanded = Vec3::Zero();  // the local model's force, device frame (N)
  Vec3 sent = Vec3::Zero();       // after ForceSafety, device frame (N)
  double torque_commanded = 0.0;  // the model's torque, device side (N·m)
  double torque_sent = 0.0;       // after ForceSafety (N·m)
  double watchdog_gain = 1.0;
  long tick = 0;                  // index since start (1 for the first)
};

struct ServoSettings {
  double rate = 1000.0;  // Hz
  DeviceFrame frame;
  SafetySettings safety;
};

/// The servo rate: 100 Hz (below, a haptic loop feels like a buzzing spring) to 10 kHz (the
/// Phantom's scheduler runs at most 1 kHz; a simulated device may go faster).
inline constexpr double kMinServoRate = 100.0;
inline constexpr double kMaxServoRate = 10000.0;
/// The servo log keeps at most 2e6 ticks (33 minutes at 1 kHz; about 270 MB, reserved before the
/// loop starts so that no tick allocates); later ticks are counted (droppedSamples), not kept.
inline constexpr std::size_t kMaxLogSamples = 2000000;

class ServoLoop {
 public:
  /// log_capacity: samples kept for the log (the servo ticks of the run), at most kMaxLogSamples.
  ServoLoop(HapticDevice& device, const ServoSettings& settings, std::size_t log_capacity);
  ~ServoLoop();
  ServoLoop(const ServoLoop&) = delete;
  ServoLoop& operator=(const ServoLoop&) = delete;

  // The servo side.
  /// One tick at servo time t; false once the loop should stop (Ctrl-C).
  bool tick(double t);
  /// Runs the ticks on the device's servo thread (HapticDevice::start).
  void startThread();
  /// Lockstep: runs the ticks due up to servo time t (k T ≤ t) on the caller's thread.
  void runLockstepUntil(double t);
  /// Stops the ticks and sends zero force. Idempotent.
  void stop();

  // The simulation side.
  /// Publishes the model for the ticks to come (sequence numbers it).
  void publish(LocalLinearModel model);
  /// The newest tick's sample, if a tick ran since the last call (else out is unchanged).
  bool latestSample(ServoSample& out);

  // After stop (or between lockstep calls): the log.
  const std::vector<ServoSample>& log() const { return log_; }
  long droppedSamples() const { return dropped_; }
  long ticks() const { return ticks_.load(); }
  const ForceSafety& safety() const { return safety_; }
  double period() const { return period_; }
  HapticDevice& device() { return device_; }
  bool interrupted() const { return interrupted_.load(); }

 private:
  HapticDevice& device_;
  ServoSettings settings_;
  double period_;
  ForceSafety safety_;
  TripleBuffer<LocalLinearModel> models_;
  TripleBuffer<ServoSample> samples_;
  std::vector<ServoSample> log_;
  std::size_t log_capacity_;
  long dropped_ = 0;
  long sequence_ = 0;       // simulation side: models published
  long last_sequence_ = 0;  // servo side: the model in use
  double last_time_ = 0.0;
  std::atomic<long> ticks_{0};
  std::atomic<bool> running_{false};
  std::atomic<bool> interrupted_{false};
};

}  // namespace filum::haptics
