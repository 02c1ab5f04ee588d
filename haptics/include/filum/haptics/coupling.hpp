// Coupling gains between the stylus and the simulated tool (the virtual coupling of Colgate,
// Stanley & Brown 1995, Adams & Hannaford 1999): a spring k and a damper c between the stylus
// position x and the tool point P, F_tool = k (x − P) + c (ẋ − Ṗ) on the tool and its opposite on
// the hand.
//
// Passivity. A device of physical damping b, sampled with period T, zero-order hold on the
// force and backward-difference velocity, rendering a virtual spring K and damper B, is passive
// if and only if (Colgate & Schenkel 1997, "Passivity of a class of sampled-data systems")
//   b > K T / 2 + |B|.
// The gains are checked against it as the hand feels them (DeviceFrame::gainToDevice). The
// default gains keep half the margin: B = 0.1 b, K = min(max_stiffness, (b − |B|) / T); with a
// Touch (b ≈ 1 N·s/m, assumed) at 1 kHz: B = 0.1 N·s/m, K = 900 N/m (its own limit is 1020 N/m).
#pragma once

#include <string>

#include "filum/core/params.hpp"
#include "filum/haptics/device_frame.hpp"
#include "filum/haptics/device_limits.hpp"

namespace filum::haptics {

struct CouplingGains {
  double stiffness = 0.0;  // k, N/m, in the scene
  double damping = 0.0;    // c, N·s/m, in the scene
};

/// b − (K T / 2 + |B|) (N·s/m): positive when the gains, felt as K and B on the device, are
/// passive at period T.
double passivityMargin(double device_damping, double stiffness, double damping, double period);

/// The default gains for a device (see above), expressed in the scene through the frame's scales.
CouplingGains defaultCoupling(const DeviceLimits& limits, const DeviceFrame& frame, double period);

/// Reads "stiffness" and "damping" (defaults: defaultCoupling) and checks them: passive at the
/// servo period and below the device's max_stiffness, as felt on the device. Throws SceneError at
/// the faulty key, naming the condition and the largest stiffness allowed.
CouplingGains couplingFromParams(const Params& p, const DeviceLimits& limits, const DeviceFrame& frame,
                                 double period);

}  // namespace filum::haptics
