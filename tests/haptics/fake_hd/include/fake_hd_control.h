// The test side of the fake HD library: plays the device (stylus, buttons, faults) and the
// scheduler (ticks run by the test, deterministic), and records what the backend did.
#pragma once

#include <string>
#include <vector>

namespace fake_hd {

struct Record {
  bool initialized = false;
  std::string device_name;            // as passed to hdInitDevice ("<default>" for HD_DEFAULT_DEVICE)
  bool force_output = false;          // hdEnable(HD_FORCE_OUTPUT)
  bool scheduler_running = false;
  unsigned long scheduler_rate = 0;   // Hz
  int frames = 0;                     // completed hdBeginFrame/hdEndFrame pairs
  std::vector<std::vector<double>> forces;  // every HD_CURRENT_FORCE set (N), in order
  std::vector<std::vector<double>> gimbal_torques;  // every HD_CURRENT_GIMBAL_TORQUE set (mN·m), in order
  std::vector<std::string> misuse;          // calls the HD API forbids (state outside a frame, ...)
};

/// Starts afresh: device at the origin, no buttons, no fault, nothing recorded.
void reset();
const Record& record();
/// The stylus as the device reports it (mm, mm/s), and its buttons.
void setStylus(double x_mm, double y_mm, double z_mm, double vx, double vy, double vz, int buttons);
/// The nominal limits the device reports (N, N, N/mm, workspace box in mm).
void setNominal(double max_force, double continuous_force, double stiffness_n_per_mm, const double box_mm[6]);
/// The gimbal's angles the device reports (rad; the last one is the stylus's roll).
void setGimbal(double a, double b, double roll);
/// The output axes the device reports (3: force only, the default; 6: with gimbal torques) and
/// its nominal largest gimbal torque (mN·m).
void setOutputAxes(int axes, double max_torque_mnm);
/// The next hdInitDevice fails (no such device).
void failNextInit();
/// Runs the scheduled callbacks once each, as one scheduler tick (only while it runs); returns
/// how many callbacks still continue.
int runSchedulerTick();

}  // namespace fake_hd
