// LocalLinearModel: what the simulation tells the 1 kHz servo loop about the force on the tool,
// linearised around the last simulated state (the multi-rate scheme of docs/haptics.md, "What
// runs", as in OpenSurgSim's VirtualToolCoupler), so that the servo never waits for a step:
//   F(x, v) = F0 + K (x − x0) + D (v − v0)
// with x, v the stylus position and velocity in the scene frame, F the force on the stylus in
// the scene frame (N), K = ∂F/∂x (N/m) and D = ∂F/∂v (N·s/m) the Jacobians at (x0, v0). For a
// grasp through the virtual coupling (tool.hpp), F = k (P − x) + c (Ṗ − v) with the thread point
// P, Ṗ frozen at the step's end: K = −k I, D = −c I, exact while the thread has not moved.
#pragma once

#include <Eigen/Core>

#include "filum/core/types.hpp"

namespace filum::haptics {

struct LocalLinearModel {
  Vec3 force = Vec3::Zero();     // F0 (N)
  Vec3 position = Vec3::Zero();  // x0 (m)
  Vec3 velocity = Vec3::Zero();  // v0 (m/s)
  Eigen::Matrix3d stiffness = Eigen::Matrix3d::Zero();  // K (N/m)
  Eigen::Matrix3d damping = Eigen::Matrix3d::Zero();    // D (N·s/m)
  double torque = 0.0;  // τ0 about the stylus's own axis (N·m), held until the next model
  double time = 0.0;   // simulated time of the state it was taken at (s)
  long sequence = 0;   // 0: no model yet (the servo sends no force)

  Vec3 evaluate(const Vec3& x, const Vec3& v) const {
    return force + stiffness * (x - position) + damping * (v - velocity);
  }
};

}  // namespace filum::haptics
