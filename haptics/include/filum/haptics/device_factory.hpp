// The devices a scene's "haptics"/"device" block names:
//   {"type": "ScriptedDevice", "model": "Touch", "waypoints": [...] | "csv": "...", "interpolation": ...}
//   {"type": "SimulatedDevice", "model": "Touch", "waypoints": ... (the hand's target),
//    "hand": {"stiffness": N/m, "damping": N·s/m}}
//   {"type": "OpenHapticsDevice", "model": "Touch", "name": "" (the default device)}
// "model" picks the preset limits (device_limits.hpp); the block "haptics"/"limits" overrides them.
#pragma once

#include <memory>

#include "filum/core/params.hpp"
#include "filum/haptics/haptic_device.hpp"

namespace filum::haptics {

/// Builds the device; `limits` are the preset with the scene's overrides. Throws SceneError at
/// the faulty key (an OpenHapticsDevice in a build without the SDK names the CMake option).
std::unique_ptr<HapticDevice> makeDevice(const Params& p, const DeviceLimits& limits);

/// Whether this build has the OpenHaptics backend (FILUM_WITH_OPENHAPTICS).
bool openHapticsAvailable();

}  // namespace filum::haptics
