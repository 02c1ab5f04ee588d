#include "filum/haptics/coupling.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace filum::haptics {

namespace {

constexpr double kDefaultDampingShare = 0.1;  // B = 0.1 b
constexpr double kDefaultMargin = 0.5;        // K T / 2 uses half of what b − |B| allows

std::string number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

}  // namespace

double passivityMargin(double device_damping, double stiffness, double damping, double period) {
  return device_damping - (stiffness * period / 2.0 + std::abs(damping));
}

CouplingGains defaultCoupling(const DeviceLimits& limits, const DeviceFrame& frame, double period) {
  const double felt_per_scene = frame.force_scale * frame.scale;  // K_device = felt_per_scene · K_scene
  const double B = kDefaultDampingShare * limits.damping;
  const double K = std::min(limits.max_stiffness, kDefaultMargin * 2.0 * (limits.damping - B) / period);
  return CouplingGains{K / felt_per_scene, B / felt_per_scene};
}

CouplingGains couplingFromParams(const Params& p, const DeviceLimits& limits, const DeviceFrame& frame,
                                 double period) {
  const CouplingGains defaults = defaultCoupling(limits, frame, period);
  CouplingGains g;
  g.stiffness = p.positive({"stiffness", "N/m"}, defaults.stiffness);
  g.damping = p.nonNegative({"damping", "N·s/m"}, defaults.damping);
  const double felt = frame.force_scale * frame.scale;
  const double K = felt * g.stiffness, B = felt * g.damping;
  if (K > limits.max_stiffness)
    p.fail("stiffness", "a stiffness the device renders, felt at most max_stiffness = " + number(limits.max_stiffness) +
                            " N/m (felt: force_scale · scale · k = " + number(K) + " N/m)");
  if (passivityMargin(limits.damping, K, B, period) <= 0.0)
    p.fail("stiffness", "passive gains, b > K T / 2 + |B| (Colgate & Schenkel 1997) with the device damping b = " +
                            number(limits.damping) + " N·s/m and T = " + number(period) + " s: felt K = " + number(K) +
                            " N/m and B = " + number(B) + " N·s/m need b > " + number(K * period / 2 + B) +
                            "; the largest stiffness with this damping is " +
                            number(std::max(0.0, 2.0 * (limits.damping - B) / period / felt)) + " N/m in the scene");
  return g;
}

}  // namespace filum::haptics
