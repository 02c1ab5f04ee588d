// ForceSafety, the last stage before a device write: each of its four rules on its own.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "filum/haptics/force_safety.hpp"

namespace filum::haptics {
namespace {

constexpr double kT = 1e-3;  // 1 kHz

TEST(ForceSafety, ANonFiniteForceIsZeroAtOnce) {
  ForceSafety safety(DeviceLimits{}, SafetySettings{}, kT);
  EXPECT_TRUE(safety.apply(Vec3(1.0, 0.0, 0.0), 0.0, true).isApprox(Vec3(1.0, 0.0, 0.0)));
  const Vec3 nan(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);
  EXPECT_EQ(safety.apply(nan, kT, true), Vec3::Zero());
  EXPECT_EQ(safety.apply(Vec3(0.0, std::numeric_limits<double>::infinity(), 0.0), 2 * kT, true), Vec3::Zero());
  EXPECT_EQ(safety.nonFiniteCount(), 2);
}

TEST(ForceSafety, PeakAndSlewRate) {
  DeviceLimits limits;  // Touch: 3.3 N peak, 2000 N/s
  ForceSafety safety(limits, SafetySettings{}, kT);
  // 10 N asked from rest: 2 N/ms up to the peak, direction kept.
  const Vec3 asked(0.0, 6.0, 8.0);
  Vec3 sent = safety.apply(asked, 0.0, true);
  EXPECT_NEAR(sent.norm(), 2.0, 1e-12);
  EXPECT_TRUE(sent.normalized().isApprox(asked.normalized()));
  sent = safety.apply(asked, kT, false);
  EXPECT_NEAR(sent.norm(), 3.3, 1e-12);
  // Down to zero: the slew limits the fall too (−2 N per ms), but for a NaN.
  sent = safety.apply(Vec3::Zero(), 2 * kT, false);
  EXPECT_NEAR(sent.norm(), 1.3, 1e-12);
}

TEST(ForceSafety, AHeldForceSettlesAtTheContinuousLimit) {
  DeviceLimits limits;  // 0.88 N continuous over 1 s
  ForceSafety safety(limits, SafetySettings{}, kT);
  Vec3 sent;
  double first_second_peak = 0.0;
  for (int k = 0; k < 10000; ++k) {  // 3 N held for 10 s, the model refreshed at every tick
    sent = safety.apply(Vec3(3.0, 0.0, 0.0), k * kT, true);
    if (k < 50) first_second_peak = std::max(first_second_peak, sent.norm());
  }
  EXPECT_NEAR(first_second_peak, 3.0, 1e-12);  // a short burst above the continuous limit passes
  // After 10 time constants the mean square is at its bound: |F| = c to e^-10 of the start.
  EXPECT_NEAR(sent.norm(), 0.88, 0.88 * 1e-3);
}

TEST(ForceSafety, TheWatchdogFadesTheForceWhenTheSimulationStops) {
  DeviceLimits limits;
  SafetySettings settings;  // 50 ms, then a 50 ms fade
  ForceSafety safety(limits, settings, kT);
  Vec3 sent;
  for (int k = 0; k <= 50; ++k) sent = safety.apply(Vec3(0.5, 0.0, 0.0), k * kT, k == 0);
  EXPECT_NEAR(sent.x(), 0.5, 1e-12);  // 50 ms without a model: still full
  EXPECT_FALSE(safety.watchdogActive());
  for (int k = 51; k <= 75; ++k) sent = safety.apply(Vec3(0.5, 0.0, 0.0), k * kT, false);
  EXPECT_NEAR(safety.watchdogGain(), 0.5, 1e-9);  // halfway through the fade (25 of 50 ticks)
  EXPECT_NEAR(sent.x(), 0.25, 1e-9);
  for (int k = 76; k <= 110; ++k) sent = safety.apply(Vec3(0.5, 0.0, 0.0), k * kT, false);
  EXPECT_EQ(sent, Vec3::Zero());
  // Models again: the force comes back as gradually.
  for (int k = 111; k <= 135; ++k) sent = safety.apply(Vec3(0.5, 0.0, 0.0), k * kT, true);
  EXPECT_NEAR(sent.x(), 0.25, 1e-9);
}

}  // namespace
}  // namespace filum::haptics
