#include "filum/haptics/simulated_device.hpp"

#include <algorithm>
#include <cmath>

namespace filum::haptics {

namespace {

constexpr double kSubstepsPerMillisecond = 20.0;  // sub-step h <= 1 ms / 20 = 50 µs

}  // namespace

SimulatedDevice::SimulatedDevice(StylusScript target, DeviceLimits limits, HandModel hand)
    : target_(std::move(target)), limits_(limits), hand_(hand) {
  x_ = target_.position(0.0);
  last_read_position_ = x_;
}

void SimulatedDevice::place(const Vec3& x, const Vec3& v) {
  x_ = x;
  v_ = v;
  last_read_position_ = x;
}

DeviceState SimulatedDevice::read(double t) {
  const double span = t - time_;
  if (span > 0.0) {
    const int substeps = std::max(1, static_cast<int>(std::ceil(span * 1e3 * kSubstepsPerMillisecond)));
    const double h = span / substeps;
    const double m = limits_.stylus_mass, b = limits_.damping;
    for (int k = 0; k < substeps; ++k) {
      const double tk = time_ + (k + 1) * h;
      // m (v⁺ − v)/h = F + k_h (X − x) − (c_h + b) v⁺, then x⁺ = x + h v⁺ (semi-implicit Euler).
      const Vec3 pull = force_ + hand_.stiffness * (target_.position(tk) - x_);
      const Vec3 v_next = (m * v_ + h * pull) / (m + h * (hand_.damping + b));
      work_ += h * force_.dot(v_next);  // ∫ F·ẋ over the sub-step, F held, ẋ = v⁺ (x⁺ − x = h v⁺)
      v_ = v_next;
      x_ += h * v_;
    }
    time_ = t;
  }
  DeviceState state;
  state.position = x_;
  state.velocity = read_once_ && t > last_read_time_ ? Vec3((x_ - last_read_position_) / (t - last_read_time_))
                                                    : Vec3::Zero();
  state.buttons = target_.buttons(t);
  state.roll = target_.roll(t);  // the hand turns the stylus as scripted (its roll's dynamics are not simulated)
  last_read_position_ = x_;
  last_read_time_ = t;
  read_once_ = true;
  return state;
}

}  // namespace filum::haptics
