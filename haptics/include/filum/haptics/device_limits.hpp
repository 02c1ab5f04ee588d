// DeviceLimits: what a haptic device can render, and the figures its coupling gains come from.
//
//   peak_force        the largest force it may send, briefly (N)
//   continuous_force  the largest force it may hold: the RMS of |F| over `continuous_window`
//                     seconds (its motors' heating; ForceSafety keeps it)
//   max_stiffness     the stiffest spring it renders without buzzing (N/m)
//   damping           b, the physical viscous damping of its mechanism (N·s/m): with the servo
//                     period T it bounds the virtual stiffness K and damping B that stay passive,
//                     b > K T / 2 + |B| (Colgate & Schenkel 1997; coupling.hpp)
//   stylus_mass       the apparent mass of the stylus tip (kg), for the SimulatedDevice
//   workspace         the box the stylus reaches, in the device frame (m)
//   peak_torque       the largest torque it sends about the stylus's own axis (N·m); 0 for the
//                     devices whose gimbal has no motor (the Touch, the Premium 1.5: 3-DOF force)
//
// Presets (devicePreset): the nominal figures 3D Systems publishes for the Touch (formerly the
// Phantom Omni) and the Phantom Premium 1.5: peak and continuous force, the lowest of the axes'
// stiffnesses, the workspace. The makers publish no damping: b and the stylus mass are
// assumptions (about 1 N·s/m and 45 g for a Touch), to be measured on each device by a free-decay
// test and set in the scene ("haptics"/"limits"/"damping"), since the default gains follow from b.
#pragma once

#include <string>

#include "filum/core/params.hpp"
#include "filum/core/types.hpp"

namespace filum::haptics {

struct DeviceLimits {
  double peak_force = 3.3;           // N
  double continuous_force = 0.88;    // N (RMS over continuous_window)
  double continuous_window = 1.0;    // s
  double max_stiffness = 1020.0;     // N/m
  double damping = 1.0;              // b, N·s/m (assumed, see above)
  double stylus_mass = 0.045;        // kg (assumed)
  double slew_rate = 2000.0;         // N/s: the fastest change of force sent (3.3 N in 1.65 ms)
  Vec3 workspace_min{-0.08, -0.06, -0.035};  // m, device frame
  Vec3 workspace_max{0.08, 0.06, 0.035};
  double peak_torque = 0.0;          // N·m (0: no torque rendered)
};

/// The nominal limits of a device model: "Touch" (alias "Omni"), "Premium" (Phantom Premium 1.5).
/// Throws std::invalid_argument naming the known models otherwise.
DeviceLimits devicePreset(const std::string& model);
/// Names of the presets, for messages: "Touch, Omni, Premium".
std::string devicePresetNames();

/// Reads "limits" overrides from p (each key optional, starting from `base`): peak_force,
/// continuous_force, continuous_window, max_stiffness, damping, stylus_mass, slew_rate,
/// workspace_min, workspace_max, peak_torque. Throws SceneError at the faulty key (continuous above peak, a
/// workspace box with min >= max).
DeviceLimits limitsFromParams(const Params& p, DeviceLimits base);

}  // namespace filum::haptics
