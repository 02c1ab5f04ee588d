#include "filum/haptics/device_limits.hpp"

#include <stdexcept>

namespace filum::haptics {

DeviceLimits devicePreset(const std::string& model) {
  DeviceLimits limits;  // the Touch's figures are the defaults
  if (model == "Touch" || model == "Omni") return limits;
  if (model == "Premium") {
    limits.peak_force = 8.5;
    limits.continuous_force = 1.4;
    limits.max_stiffness = 3500.0;
    limits.damping = 2.0;       // assumed, as for the Touch
    limits.stylus_mass = 0.075;  // assumed
    limits.slew_rate = 5000.0;
    limits.workspace_min = Vec3(-0.0955, -0.065, -0.0375);
    limits.workspace_max = Vec3(0.0955, 0.065, 0.0375);
    return limits;
  }
  throw std::invalid_argument("a device model among " + devicePresetNames() + ", found \"" + model + "\"");
}

std::string devicePresetNames() { return "Touch, Omni, Premium"; }

DeviceLimits limitsFromParams(const Params& p, DeviceLimits base) {
  DeviceLimits l = base;
  l.peak_force = p.positive({"peak_force", "N"}, l.peak_force);
  l.continuous_force = p.positive({"continuous_force", "N"}, l.continuous_force);
  l.continuous_window = p.positive({"continuous_window", "s"}, l.continuous_window);
  l.max_stiffness = p.positive({"max_stiffness", "N/m"}, l.max_stiffness);
  l.damping = p.positive({"damping", "N·s/m"}, l.damping);
  l.stylus_mass = p.positive({"stylus_mass", "kg"}, l.stylus_mass);
  l.slew_rate = p.positive({"slew_rate", "N/s"}, l.slew_rate);
  l.workspace_min = p.vec3({"workspace_min", "m"}, l.workspace_min);
  l.workspace_max = p.vec3({"workspace_max", "m"}, l.workspace_max);
  l.peak_torque = p.nonNegative({"peak_torque", "N·m"}, l.peak_torque);
  if (l.continuous_force > l.peak_force)
    p.fail("continuous_force", "a continuous force at most the peak force (" + std::to_string(l.peak_force) + " N)");
  if ((l.workspace_max - l.workspace_min).minCoeff() <= 0.0)
    p.fail("workspace_max", "a workspace box with every coordinate above workspace_min");
  return l;
}

}  // namespace filum::haptics
