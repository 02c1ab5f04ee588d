#include "filum/haptics/device_factory.hpp"

#include <stdexcept>

#include "filum/haptics/scripted_device.hpp"
#include "filum/haptics/simulated_device.hpp"
#if FILUM_WITH_OPENHAPTICS
#include "filum/haptics/openhaptics_device.hpp"
#endif

namespace filum::haptics {

bool openHapticsAvailable() { return FILUM_WITH_OPENHAPTICS != 0; }

std::unique_ptr<HapticDevice> makeDevice(const Params& p, const DeviceLimits& limits) {
  const std::string type = p.string("type");
  if (type == "ScriptedDevice") return std::make_unique<ScriptedDevice>(StylusScript::fromParams(p), limits);
  if (type == "SimulatedDevice") {
    HandModel hand;
    if (p.has("hand")) {
      const Params h = p.object("hand");
      hand.stiffness = h.nonNegative({"stiffness", "N/m"}, hand.stiffness);
      hand.damping = h.nonNegative({"damping", "N·s/m"}, hand.damping);
      h.finish();
    }
    return std::make_unique<SimulatedDevice>(StylusScript::fromParams(p), limits, hand);
  }
  if (type == "OpenHapticsDevice") {
    const std::string name = p.string("name", "");
#if FILUM_WITH_OPENHAPTICS
    try {
      return std::make_unique<OpenHapticsDevice>(name, limits);
    } catch (const std::runtime_error& e) {
      p.fail("type", "a Phantom that OpenHaptics opens", e.what());
    }
#else
    (void)name;
    p.fail("type", "a device this build has: ScriptedDevice or SimulatedDevice (OpenHapticsDevice needs the "
                   "OpenHaptics SDK: configure with -DFILUM_WITH_OPENHAPTICS=ON)",
           "\"OpenHapticsDevice\" in a build without the SDK");
#endif
  }
  p.fail("type", "ScriptedDevice, SimulatedDevice or OpenHapticsDevice", "\"" + type + "\"");
}

}  // namespace filum::haptics
