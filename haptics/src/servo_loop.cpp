#include "filum/haptics/servo_loop.hpp"

#include <cmath>
#include <stdexcept>

#include "filum/haptics/interrupt.hpp"

namespace filum::haptics {

ServoLoop::ServoLoop(HapticDevice& device, const ServoSettings& settings, std::size_t log_capacity)
    : device_(device),
      settings_(settings),
      period_(1.0 / settings.rate),
      safety_(device.limits(), settings.safety, 1.0 / settings.rate),
      log_capacity_(log_capacity) {
  if (!(settings.rate >= kMinServoRate && settings.rate <= kMaxServoRate))
    throw std::invalid_argument("a servo rate in [100, 10000] Hz, found " + std::to_string(settings.rate));
  if (log_capacity > kMaxLogSamples)
    throw std::invalid_argument("a servo log of at most " + std::to_string(kMaxLogSamples) + " samples, found " +
                                std::to_string(log_capacity));
  log_.reserve(log_capacity);  // the only allocation: ticks append without allocating
}

ServoLoop::~ServoLoop() { stop(); }

bool ServoLoop::tick(double t) {
  if (interruptRequested()) {
    interrupted_.store(true);
    device_.write(Vec3::Zero());
    device_.writeTorque(0.0);
    return false;
  }
  const DeviceState stylus = device_.read(t);
  ServoSample sample;
  sample.time = t;
  sample.tick = ticks_.load(std::memory_order_relaxed) + 1;
  sample.period = sample.tick == 1 ? period_ : t - last_time_;
  last_time_ = t;
  sample.position = settings_.frame.positionToScene(stylus.position);
  sample.velocity = settings_.frame.velocityToScene(stylus.velocity);
  sample.buttons = stylus.buttons;
  sample.roll = stylus.roll;
  const bool fresh = models_.read() && models_.latest().sequence != last_sequence_;
  const LocalLinearModel& model = models_.latest();
  last_sequence_ = model.sequence;
  // No model yet: no force (the watchdog would fade it anyway; the first model starts from 0).
  const Vec3 scene_force = model.sequence == 0 ? Vec3::Zero() : model.evaluate(sample.position, sample.velocity);
  sample.commanded = settings_.frame.forceToDevice(scene_force);
  sample.sent = safety_.apply(sample.commanded, t, fresh);
  sample.watchdog_gain = safety_.watchdogGain();
  sample.torque_commanded = model.sequence == 0 ? 0.0 : settings_.frame.force_scale * model.torque;
  sample.torque_sent = safety_.applyTorque(sample.torque_commanded);
  device_.write(sample.sent);
  device_.writeTorque(sample.torque_sent);
  samples_.write(sample);
  if (log_.size() < log_capacity_) {
    log_.push_back(sample);
  } else {
    ++dropped_;
  }
  ticks_.fetch_add(1, std::memory_order_release);
  return true;
}

void ServoLoop::startThread() {
  if (running_.exchange(true)) return;
  device_.start([this](double t) { return tick(t); }, settings_.rate);
}

void ServoLoop::runLockstepUntil(double t) {
  if (!device_.canRunLockstep()) throw std::logic_error(device_.name() + " runs on the wall clock, not in lockstep");
  // Tick k runs at servo time k T, from k = 0. The 1e-6 T only decides on which side of a step
  // boundary a tick falls when t and k T agree but for round-off: either side is right, and the
  // choice is the same on every run (determinism).
  for (long k = ticks_.load(); static_cast<double>(k) * period_ <= t + 1e-6 * period_; k = ticks_.load())
    if (!tick(static_cast<double>(k) * period_)) break;
}

void ServoLoop::stop() {
  if (running_.exchange(false)) device_.stop();  // joins the servo thread, leaves zero force
  device_.write(Vec3::Zero());
  device_.writeTorque(0.0);
}

void ServoLoop::publish(LocalLinearModel model) {
  model.sequence = ++sequence_;
  models_.write(model);
}

bool ServoLoop::latestSample(ServoSample& out) {
  if (!samples_.read()) return false;
  out = samples_.latest();
  return true;
}

}  // namespace filum::haptics
