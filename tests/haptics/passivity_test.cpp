// Colgate's passivity condition, b > K T / 2 + |B|, in closed loop: a free SimulatedDevice (the
// hand let go, hand stiffness 0) against the servo loop rendering a virtual spring K and damper B
// to a fixed point — what the virtual coupling renders while the thread point is still. The
// energy of stylus and virtual spring, E = ½ m ẋ² + ½ K x², starts at E0 = ½ K x0². A passive
// loop never lets it exceed E0 (nothing in it can create energy) and the device's damping drains
// it; a loop that violates the condition pumps energy into every oscillation (the zero-order
// hold acts as a negative damping K T / 2) and E grows without bound. The device's force limits
// are lifted here so that only the gains decide.
#include <gtest/gtest.h>

#include "filum/core/scene_error.hpp"
#include "filum/haptics/coupling.hpp"
#include "filum/haptics/servo_loop.hpp"
#include "filum/haptics/simulated_device.hpp"

namespace filum::haptics {
namespace {

constexpr double kRate = 1000.0;
constexpr double kPeriod = 1.0 / kRate;

struct Outcome {
  double initial_energy = 0.0;  // E0 (J)
  double largest_energy = 0.0;  // max over the run of E (J)
  double final_energy = 0.0;    // E after 2 s (J)
};

/// 2 s of the stylus released 0.2 mm from the spring's rest point.
Outcome release(const CouplingGains& gains) {
  DeviceLimits limits = devicePreset("Touch");  // its damping b and stylus mass; no force limits:
  limits.peak_force = limits.continuous_force = 1e6;
  limits.slew_rate = 1e12;
  StylusScript still({{0.0, Vec3::Zero()}}, {0u}, geometry::ScriptedPath::Interpolation::kLinear);
  SimulatedDevice device(still, limits, HandModel{0.0, 0.0});
  const double x0 = 2e-4;
  device.place(Vec3(x0, 0.0, 0.0), Vec3::Zero());
  ServoSettings settings;
  settings.rate = kRate;
  ServoLoop servo(device, settings, 0);
  LocalLinearModel spring;
  spring.stiffness = -gains.stiffness * Eigen::Matrix3d::Identity();
  spring.damping = -gains.damping * Eigen::Matrix3d::Identity();
  Outcome out;
  out.initial_energy = 0.5 * gains.stiffness * x0 * x0;
  for (int k = 0; k < 2000; ++k) {
    servo.publish(spring);  // the simulation's model, every millisecond
    servo.runLockstepUntil(k * kPeriod);
    const Vec3 x = device.truePosition(), v = device.trueVelocity();
    out.final_energy = 0.5 * limits.stylus_mass * v.squaredNorm() + 0.5 * gains.stiffness * x.squaredNorm();
    out.largest_energy = std::max(out.largest_energy, out.final_energy);
  }
  return out;
}

TEST(Passivity, TheDefaultGainsMeetColgatesCondition) {
  const DeviceLimits touch = devicePreset("Touch");
  const CouplingGains gains = defaultCoupling(touch, DeviceFrame{}, kPeriod);
  EXPECT_GT(passivityMargin(touch.damping, gains.stiffness, gains.damping, kPeriod), 0.0);
  EXPECT_LE(gains.stiffness, touch.max_stiffness);
}

TEST(Passivity, WithTheDefaultGainsTheEnergyNeverGrowsAndDrains) {
  const CouplingGains gains = defaultCoupling(devicePreset("Touch"), DeviceFrame{}, kPeriod);
  const Outcome o = release(gains);
  // Passive: E(t) ≤ E0 throughout (the factor 1 + 1e-9 only absorbs the round-off of the sums).
  EXPECT_LE(o.largest_energy, o.initial_energy * (1.0 + 1e-9)) << "E0 = " << o.initial_energy;
  // Drained: the slowest mode decays as e^{−ζ ω t} with ζ ω ≥ (b − K T/2 − B)/(2 m) ≈ 5 1/s
  // (the margin over twice the stylus mass): after 2 s, E/E0 ≤ e^{−20} ≈ 2e-9.
  EXPECT_LT(o.final_energy, 2e-9 * o.initial_energy) << "E0 = " << o.initial_energy;
}

TEST(Passivity, GainsThatViolateTheConditionPumpEnergyIn) {
  const DeviceLimits touch = devicePreset("Touch");
  // Twice the stiffness the condition allows with B = 0.1 b: K = 2 · 2 (b − B) / T.
  CouplingGains gains{2.0 * 2.0 * (touch.damping - 0.1 * touch.damping) / kPeriod, 0.1 * touch.damping};
  ASSERT_LT(passivityMargin(touch.damping, gains.stiffness, gains.damping, kPeriod), 0.0);
  const Outcome o = release(gains);
  // Not passive: E exceeds E0, which no passive loop allows, and keeps growing (by orders of
  // magnitude in 2 s); 100 E0 leaves no doubt.
  EXPECT_GT(o.final_energy, 100.0 * o.initial_energy) << "E0 = " << o.initial_energy;
}

TEST(Passivity, ASceneAskingForNonPassiveGainsIsRefusedAtItsPath) {
  const nlohmann::json coupling = {{"stiffness", 5000.0}};
  const Params p(coupling, "grasp.json", "/haptics/coupling");
  try {
    couplingFromParams(p, devicePreset("Touch"), DeviceFrame{}, kPeriod);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("grasp.json: /haptics/coupling/stiffness"), std::string::npos) << message;
    EXPECT_NE(message.find("max_stiffness"), std::string::npos) << message;
  }
  const nlohmann::json damped = {{"stiffness", 900.0}, {"damping", 0.8}};  // K T/2 + B = 1.25 > b = 1
  try {
    couplingFromParams(Params(damped, "grasp.json", "/haptics/coupling"), devicePreset("Touch"), DeviceFrame{}, kPeriod);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("Colgate"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace filum::haptics
