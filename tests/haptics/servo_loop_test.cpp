// The servo loop: ticks on the servo grid in lockstep, the stylus mapped into the scene frame,
// the local linear model evaluated there and its force mapped back, and the threaded mode
// started and stopped with the force left at zero.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "filum/core/scene_error.hpp"
#include "filum/haptics/scripted_device.hpp"
#include "filum/haptics/servo_loop.hpp"

namespace filum::haptics {
namespace {

StylusScript line() {
  // 1 cm along device x in 1 s, button 1 from 0.5 s.
  return StylusScript({{0.0, Vec3::Zero()}, {0.5, Vec3(0.005, 0, 0)}, {1.0, Vec3(0.01, 0, 0)}}, {0u, 1u, 1u},
                      geometry::ScriptedPath::Interpolation::kLinear);
}

TEST(ServoLoop, LockstepTicksFollowTheScriptInTheSceneFrame) {
  ScriptedDevice device(line(), devicePreset("Touch"));
  ServoSettings settings;
  settings.frame.rotation << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // "y_up"
  settings.frame.scale = 0.5;
  settings.frame.offset = Vec3(0.1, 0.2, 0.3);
  ServoLoop servo(device, settings, 2000);
  servo.runLockstepUntil(0.7);
  EXPECT_EQ(servo.ticks(), 701);  // t = 0, 1 ms, ..., 700 ms
  ServoSample s;
  ASSERT_TRUE(servo.latestSample(s));
  EXPECT_DOUBLE_EQ(s.time, 0.7);
  EXPECT_EQ(s.buttons, 1u);
  // Device x = 7 mm → scene offset + 0.5 · 7 mm along x; velocity 1 cm/s · 0.5.
  EXPECT_TRUE(s.position.isApprox(Vec3(0.1035, 0.2, 0.3), 1e-12)) << s.position.transpose();
  EXPECT_TRUE(s.velocity.isApprox(Vec3(0.005, 0.0, 0.0), 1e-12)) << s.velocity.transpose();
  EXPECT_FALSE(servo.latestSample(s));  // nothing new since
}

TEST(ServoLoop, TheModelsForceIsMappedBackToTheDevice) {
  ScriptedDevice device(line(), devicePreset("Touch"));
  ServoSettings settings;
  settings.frame.rotation << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // device y = scene z
  settings.frame.force_scale = 2.0;
  ServoLoop servo(device, settings, 10);
  LocalLinearModel model;
  model.force = Vec3(0.0, 0.0, 0.25);  // 0.25 N up in the scene
  servo.publish(model);
  servo.runLockstepUntil(0.0);
  // Scene z is device y; force_scale 2: 0.5 N along device y.
  EXPECT_TRUE(device.lastForce().isApprox(Vec3(0.0, 0.5, 0.0), 1e-12)) << device.lastForce().transpose();
  servo.stop();
  EXPECT_EQ(device.lastForce(), Vec3::Zero());
}

TEST(ServoLoop, TheStylusRollIsReadAndTheModelsTorqueSentWithinThePeakTorque) {
  // The roll turns 0.4 rad over 1 s; the model asks 0.02 N·m about the stylus's axis.
  StylusScript script({{0.0, Vec3::Zero()}, {1.0, Vec3::Zero()}}, {0u, 0u}, geometry::ScriptedPath::Interpolation::kLinear,
                      {0.0, 0.4});
  DeviceLimits limits = devicePreset("Touch");
  limits.peak_torque = 0.05;  // N·m: a gimbal with a motor
  ScriptedDevice device(script, limits);
  ServoSettings settings;
  settings.frame.force_scale = 2.0;  // torques as forces: 2 device N·m per scene N·m
  ServoLoop servo(device, settings, 1000);
  LocalLinearModel model;
  model.torque = 0.02;
  servo.publish(model);
  servo.runLockstepUntil(0.03);  // (within the watchdog's 50 ms of the model)
  ServoSample s;
  ASSERT_TRUE(servo.latestSample(s));
  EXPECT_NEAR(s.roll, 0.012, 1e-15);  // linear: 0.4 · 0.03 (round-off of the interpolation)
  EXPECT_DOUBLE_EQ(s.torque_commanded, 0.04);
  EXPECT_DOUBLE_EQ(s.torque_sent, 0.04);
  EXPECT_DOUBLE_EQ(device.lastTorque(), 0.04);
  // Beyond the peak: clamped (reached within the force's rise time, 0.05 · 2000 / 3.3 N·m a second
  // of slew: 3 ticks); not finite: zero, counted.
  model.torque = -0.5;
  servo.publish(model);
  servo.runLockstepUntil(0.04);
  EXPECT_DOUBLE_EQ(device.lastTorque(), -0.05);
  model.torque = std::nan("");
  servo.publish(model);
  servo.runLockstepUntil(0.05);
  EXPECT_EQ(device.lastTorque(), 0.0);
  EXPECT_GE(servo.safety().nonFiniteTorqueCount(), 1);
  EXPECT_EQ(servo.safety().nonFiniteCount(), 0);  // the force was finite
  servo.stop();
  EXPECT_EQ(device.lastTorque(), 0.0);
}

TEST(ServoLoop, ADeviceWithoutTorqueGetsNone) {
  ScriptedDevice device(line(), devicePreset("Touch"));  // peak_torque 0: no motor on the gimbal
  ServoLoop servo(device, ServoSettings{}, 10);
  LocalLinearModel model;
  model.torque = 0.02;
  servo.publish(model);
  servo.runLockstepUntil(0.0);
  ServoSample s;
  ASSERT_TRUE(servo.latestSample(s));
  EXPECT_DOUBLE_EQ(s.torque_commanded, 0.02);  // asked for (haptics.csv shows it) ...
  EXPECT_EQ(s.torque_sent, 0.0);               // ... not sent
  EXPECT_EQ(device.lastTorque(), 0.0);
}

TEST(ServoLoop, TheThreadTicksUntilStoppedAndLeavesZeroForce) {
  ScriptedDevice device(line(), devicePreset("Touch"));
  ServoSettings settings;
  ServoLoop servo(device, settings, 100000);
  LocalLinearModel model;
  model.force = Vec3(0.1, 0.0, 0.0);
  servo.publish(model);
  servo.startThread();
  // No timing is asserted (benchmarks measure it): only that ticks happen, within a generous wait.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (servo.ticks() < 20 && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  servo.stop();
  EXPECT_GE(servo.ticks(), 20);
  EXPECT_EQ(device.lastForce(), Vec3::Zero());
  const long ticks = servo.ticks();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(servo.ticks(), ticks);  // stopped for good
  ASSERT_FALSE(servo.log().empty());
  for (std::size_t k = 1; k < servo.log().size(); ++k) EXPECT_GT(servo.log()[k].time, servo.log()[k - 1].time);
}

}  // namespace
}  // namespace filum::haptics

namespace filum::haptics {
namespace {

TEST(StylusScript, ReadsACsvAndRefusesABadRowAtItsLine) {
  const std::string dir = std::string(FILUM_BINARY_DIR) + "/test_output";
  std::filesystem::create_directories(dir);
  const std::string good = dir + "/stylus.csv", bad = dir + "/stylus_bad.csv";
  const std::string bad_roll = dir + "/stylus_bad_roll.csv";
  std::ofstream(good) << "time,x,y,z,buttons,roll\n0,0,0,0\n0.5,0.01,0,0,1,0.2\n1.0,0.02,0,0,0,0.6\n";
  std::ofstream(bad) << "time,x,y,z,buttons\n0,0,0,0,0\n0.5,0.01,0,0,one\n";
  std::ofstream(bad_roll) << "time,x,y,z,buttons,roll\n0,0,0,0,0,0\n0.5,0.01,0,0,1,nan\n";
  const nlohmann::json p_good = {{"csv", good}}, p_bad = {{"csv", bad}}, p_bad_roll = {{"csv", bad_roll}};
  const StylusScript script = StylusScript::fromParams(Params(p_good, "scene.json", "/haptics/device"));
  EXPECT_TRUE(script.position(0.75).isApprox(Vec3(0.015, 0, 0), 1e-12));
  EXPECT_EQ(script.buttons(0.6), 1u);
  EXPECT_EQ(script.buttons(1.2), 0u);
  EXPECT_NEAR(script.roll(0.75), 0.4, 1e-15);  // the sixth column, interpolated
  EXPECT_NEAR(script.roll(0.25), 0.1, 1e-15);    // (0 in the first row, which has none)
  for (const auto& [file, params] : {std::pair{bad, p_bad}, std::pair{bad_roll, p_bad_roll}}) {
    try {
      StylusScript::fromParams(Params(params, "scene.json", "/haptics/device"));
      FAIL() << file << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(file + ":3"), std::string::npos) << e.what();
    }
  }
}

TEST(StylusScript, AWaypointsRollHoldsTillTheNextOneGivesAnother) {
  const nlohmann::json p = {{"waypoints", {{{"time", 0.0}, {"position", {0, 0, 0}}},
                                           {{"time", 1.0}, {"position", {0, 0, 0}}, {"roll", 1.0}},
                                           {{"time", 2.0}, {"position", {0, 0, 0}}}}}};
  const StylusScript script = StylusScript::fromParams(Params(p, "scene.json", "/haptics/device"));
  EXPECT_NEAR(script.roll(0.5), 0.5, 1e-15);
  EXPECT_NEAR(script.roll(1.5), 1.0, 1e-15);  // the third waypoint keeps the second's roll
}

}  // namespace
}  // namespace filum::haptics
