#include "filum/haptics/force_safety.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace filum::haptics {

ForceSafety::ForceSafety(const DeviceLimits& limits, SafetySettings settings, double period)
    : limits_(limits), settings_(settings), period_(period), alpha_(std::min(1.0, period / limits.continuous_window)) {
  if (!(period > 0.0) || !(settings.fade > 0.0) || !(settings.watchdog > 0.0))
    throw std::invalid_argument("ForceSafety: period, watchdog and fade must be positive");
}

Vec3 ForceSafety::apply(const Vec3& commanded, double t, bool fresh) {
  // 2. watchdog (its gain first: the torque of this tick takes it even when the force is refused)
  if (fresh) last_model_time_ = t;
  const double rate = period_ / settings_.fade;
  gain_ = t - last_model_time_ > settings_.watchdog ? std::max(0.0, gain_ - rate) : std::min(1.0, gain_ + rate);
  Vec3 F = commanded;
  if (!F.allFinite()) {  // 1. at once: no slew toward a force that no longer means anything
    ++non_finite_;
    mean_square_ *= 1.0 - alpha_;
    last_.setZero();
    return last_;
  }
  F *= gain_;
  // 3. slew rate (before the limits: a limit may cut the force faster than the slew rate, never raise it)
  const Vec3 change = F - last_;
  const double max_change = limits_.slew_rate * period_;
  if (const double size = change.norm(); size > max_change) F = last_ + change * (max_change / size);
  // 4. peak and continuous limits
  const double c2 = limits_.continuous_force * limits_.continuous_force;
  const double heat_room = mean_square_ + (c2 - mean_square_) / alpha_;
  const double largest = std::min(limits_.peak_force, std::sqrt(std::max(0.0, heat_room)));
  if (const double size = F.norm(); size > largest) F *= largest / size;
  mean_square_ += alpha_ * (F.squaredNorm() - mean_square_);
  last_ = F;
  return F;
}

double ForceSafety::applyTorque(double commanded) {
  if (!(limits_.peak_torque > 0.0)) return 0.0;  // no motor on the gimbal
  if (!std::isfinite(commanded)) {
    ++non_finite_torques_;
    last_torque_ = 0.0;
    return 0.0;
  }
  // The force's rise time, peak / slew rate, for the torque too: no jolt at a grip or a release.
  const double max_change = limits_.peak_torque * limits_.slew_rate / limits_.peak_force * period_;
  const double target = std::clamp(gain_ * commanded, -limits_.peak_torque, limits_.peak_torque);
  last_torque_ = std::clamp(target, last_torque_ - max_change, last_torque_ + max_change);
  return last_torque_;
}

}  // namespace filum::haptics
