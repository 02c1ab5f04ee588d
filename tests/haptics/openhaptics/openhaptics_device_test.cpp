// The OpenHaptics backend against the fake HD library: the calls the HD API requires (state
// only inside frames, force output enabled before forces, the scheduler at the servo rate), its
// units (mm, mm/s and N/mm in; N out), and the servo loop's safety as the device sees it: forces
// within the clamp, zero after a NaN, zero when stopped.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fake_hd_control.h"
#include "filum/haptics/openhaptics_device.hpp"
#include "filum/haptics/servo_loop.hpp"

namespace filum::haptics {
namespace {

class OpenHapticsDeviceTest : public ::testing::Test {
 protected:
  void SetUp() override { fake_hd::reset(); }
  void TearDown() override { EXPECT_TRUE(fake_hd::record().misuse.empty()) << fake_hd::record().misuse.front(); }
};

TEST_F(OpenHapticsDeviceTest, ReadsTheNominalLimitsInSIUnits) {
  const double box[6] = {-100, -50, -40, 120, 70, 30};
  fake_hd::setNominal(8.5, 1.4, 3.5, box);
  OpenHapticsDevice device("Left Phantom", devicePreset("Premium"));
  EXPECT_EQ(fake_hd::record().device_name, "Left Phantom");
  EXPECT_TRUE(fake_hd::record().force_output);
  EXPECT_DOUBLE_EQ(device.limits().peak_force, 8.5);
  EXPECT_DOUBLE_EQ(device.limits().continuous_force, 1.4);
  EXPECT_DOUBLE_EQ(device.limits().max_stiffness, 3500.0);  // 3.5 N/mm
  EXPECT_TRUE(device.limits().workspace_min.isApprox(Vec3(-0.1, -0.05, -0.04)));
  EXPECT_TRUE(device.limits().workspace_max.isApprox(Vec3(0.12, 0.07, 0.03)));
  EXPECT_DOUBLE_EQ(device.limits().damping, devicePreset("Premium").damping);  // not reported: the preset's
  EXPECT_FALSE(device.canRunLockstep());
}

TEST_F(OpenHapticsDeviceTest, AFailedInitNamesTheCallAndTheError) {
  fake_hd::failNextInit();
  try {
    OpenHapticsDevice device("", devicePreset("Touch"));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("hdInitDevice"), std::string::npos) << message;
    EXPECT_NE(message.find("no such device"), std::string::npos) << message;
    EXPECT_NE(message.find("42"), std::string::npos) << message;  // the device's own code
  }
}

TEST_F(OpenHapticsDeviceTest, TheServoLoopRunsInHDFramesWithSafeForcesInNewtons) {
  OpenHapticsDevice device("", devicePreset("Touch"));
  EXPECT_EQ(fake_hd::record().device_name, "<default>");
  ServoSettings settings;  // identity frame, 1 kHz
  ServoLoop servo(device, settings, 100);
  servo.startThread();
  EXPECT_TRUE(fake_hd::record().scheduler_running);
  EXPECT_EQ(fake_hd::record().scheduler_rate, 1000u);

  // The stylus 10 mm right, moving 20 mm/s up, button 1 held: the servo sees metres.
  fake_hd::setStylus(10.0, 0.0, 0.0, 0.0, 20.0, 0.0, 1);
  // A spring of 200 N/m toward the origin: 2 N at 10 mm, within the Touch's 3.3 N peak... after
  // the slew limit (2000 N/s: 2 N/ms): the first tick sends 2 N, the next the same.
  LocalLinearModel model;
  model.stiffness = -200.0 * Eigen::Matrix3d::Identity();
  servo.publish(model);
  ASSERT_EQ(fake_hd::runSchedulerTick(), 1);
  ServoSample sample;
  ASSERT_TRUE(servo.latestSample(sample));
  EXPECT_TRUE(sample.position.isApprox(Vec3(0.01, 0.0, 0.0)));
  EXPECT_TRUE(sample.velocity.isApprox(Vec3(0.0, 0.02, 0.0)));
  EXPECT_EQ(sample.buttons, 1u);
  ASSERT_EQ(fake_hd::record().forces.size(), 1u);
  EXPECT_NEAR(fake_hd::record().forces.back()[0], -2.0, 1e-12);  // N, the spring's force; the slew allows 2 N/ms

  // 100 mm away: 20 N commanded, the peak (3.3 N) sent.
  fake_hd::setStylus(100.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0);
  for (int k = 0; k < 5; ++k) fake_hd::runSchedulerTick();
  const auto& f = fake_hd::record().forces.back();
  EXPECT_NEAR(std::hypot(f[0], f[1], f[2]), 3.3, 1e-12);

  // A NaN in the model: zero at once (no slew toward it).
  model.force = Vec3(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);
  servo.publish(model);
  fake_hd::runSchedulerTick();
  EXPECT_EQ(fake_hd::record().forces.back(), (std::vector<double>{0.0, 0.0, 0.0}));
  EXPECT_EQ(servo.safety().nonFiniteCount(), 1);

  // Stop: the scheduler ends, one last zero force, force output off.
  const int frames = fake_hd::record().frames;
  servo.stop();
  EXPECT_FALSE(fake_hd::record().scheduler_running);
  EXPECT_EQ(fake_hd::record().frames, frames + 1);
  EXPECT_EQ(fake_hd::record().forces.back(), (std::vector<double>{0.0, 0.0, 0.0}));
  EXPECT_FALSE(fake_hd::record().force_output);
  for (const auto& sent : fake_hd::record().forces)
    EXPECT_LE(std::hypot(sent[0], sent[1], sent[2]), 3.3 + 1e-12);  // every force within the clamp
}

TEST_F(OpenHapticsDeviceTest, TheRollIsTheLastGimbalAngleAndATorqueGoesOnlyToASixAxisDevice) {
  // A Touch (three output axes): the roll is read, a torque is never set.
  {
    OpenHapticsDevice device("", devicePreset("Touch"));
    EXPECT_EQ(device.limits().peak_torque, 0.0);
    ServoLoop servo(device, ServoSettings{}, 100);
    servo.startThread();
    fake_hd::setGimbal(0.1, 0.2, 0.7);
    LocalLinearModel model;
    model.torque = 0.01;
    servo.publish(model);
    fake_hd::runSchedulerTick();
    ServoSample sample;
    ASSERT_TRUE(servo.latestSample(sample));
    EXPECT_EQ(sample.roll, 0.7);
    EXPECT_EQ(sample.torque_sent, 0.0);
    servo.stop();
    EXPECT_TRUE(fake_hd::record().gimbal_torques.empty());
  }
  // Six output axes, 188 mN·m nominal: the torque set on the last joint in mN·m.
  fake_hd::reset();
  fake_hd::setOutputAxes(6, 188.0);
  OpenHapticsDevice device("", devicePreset("Premium"));
  EXPECT_DOUBLE_EQ(device.limits().peak_torque, 0.188);
  ServoLoop servo(device, ServoSettings{}, 100);
  servo.startThread();
  LocalLinearModel model;
  model.torque = -0.05;
  servo.publish(model);
  fake_hd::runSchedulerTick();
  ASSERT_FALSE(fake_hd::record().gimbal_torques.empty());
  EXPECT_EQ(fake_hd::record().gimbal_torques.back(), (std::vector<double>{0.0, 0.0, -50.0}));
  servo.stop();
  EXPECT_EQ(fake_hd::record().gimbal_torques.back(), (std::vector<double>{0.0, 0.0, 0.0}));  // left at zero
}

}  // namespace
}  // namespace filum::haptics
