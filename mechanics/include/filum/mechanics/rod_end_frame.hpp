// RodEndFrame: an end of a FramedChain built in — its material frame held at a direction and a
// roll angle, fixed or following a path in time (a cantilever's clamp; the hub of a catheter or
// guidewire pushed and turned by the hand). The rod's own bending and twist join the held frame
// R_h, at the end node, to the end segment's frame R_e, whose centre lies half a segment in:
//   E = ½ (φ − φ̄)ᵀ B (φ − φ̄) / ℓ,   φ = log(R_hᵀ R_0) at the start (log(R_eᵀ R_h) at the end),
//   ℓ = l_e / 2,  B = diag(E I, E I, G J) of the end segment (the body's ChainElasticity),
//   φ̄ = ∫ κ̄ ds over that half segment (the rest shape; 0 with "rest_shape": "initial"),
// the term ChainElasticity puts at every interior node, over the end node's half cell. So the
// curvature reaches the end: holding only the first segment's direction (ClampConstraint on the
// polyline's tangent) leaves half a segment rigid at the clamp, a first-order error in the
// segment length (a cantilever's tip deflection 3 l / 2L short: 7.5 % at 21 nodes); with the
// half-segment term the rod converges at second order (tests/mechanics/rod_mechanics_test.cpp).
// Torques on the end frame (body frame, right increments): −J_r⁻¹(φ)ᵀ m at the start,
// +J_l⁻¹(φ)ᵀ m at the end, m = B (φ − φ̄) / ℓ (chain_elasticity.hpp).
//
// The held frame: R_h(t) = Rot(ψ(t), d(t)) · Rot(d₀ → d(t)) · R₀, with R₀ the end segment's
// initial frame, d₀ its tangent, Rot(d₀ → d) the shortest turn and ψ the roll about d. A path
// gives (time, direction, roll) keyframes: roll linear in time, direction along the great circle
// (normalized linear interpolation), held before the first and after the last keyframe.
// The end's position is held separately, by a FixedPointConstraint at the same abscissa (with a
// "path" to push the rod). The body's ChainElasticity must come before this component.
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <vector>

#include "filum/core/force_field.hpp"
#include "filum/core/params.hpp"

namespace filum::mechanics {

class FramedChain;

class RodEndFrame final : public ForceField {
 public:
  enum class End { kStart, kFinish };
  struct Keyframe {
    double time = 0.0;                   // s
    std::optional<Vec3> direction;       // unit; nullopt: the end segment's initial tangent
    double roll = 0.0;                   // rad
  };
  /// One keyframe: a fixed frame.
  RodEndFrame(End end, std::vector<Keyframe> keyframes) : end_(end), keyframes_(std::move(keyframes)) {}
  /// "end": "start" (default, s = 0) or "end" (s = 1); "direction": [x, y, z] (default: the end
  /// segment's initial tangent) and "roll": rad (default 0), or "path": [{"time": s,
  /// "direction": [...], "roll": rad}, ...] (times increasing).
  static std::unique_ptr<RodEndFrame> fromParams(const Params& p);

  std::string typeName() const override { return "RodEndFrame"; }
  void addForce(const SceneState& s, VecX& B) const override;
  double potentialEnergy(const SceneState& s) const override;
  /// The Gauss–Newton Hessian J⁻ᵀ (B / ℓ) J⁻¹ on the end frame (J_r⁻¹ at the start, J_l⁻¹ at
  /// the end; chain_elasticity.hpp says what it leaves out).
  void addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const override;
  bool hasJacobian() const override { return true; }

  /// Which end it holds.
  End end() const { return end_; }
  /// The node's RodEndFrame at the start (s = 0: a hub's), not one holding the far end (a tip);
  /// nullptr when it has none.
  static RodEndFrame* atStartOf(const Node& node);
  /// The held frame at time t.
  Eigen::Quaterniond heldFrame(double t) const;
  /// The roll ψ(t) the path holds the end at (rad): how far the hand has turned the hub.
  double roll(double t) const { return poseAt(t).second; }
  /// The hand turns the hub (`filum view`'s keys, haptics/hub_control.hpp): from t0 the roll goes
  /// linearly to roll(t0) + angle at t1 > t0 and is held there, the direction held as at t0. The
  /// path given in the scene is dropped from t0 on.
  void turn(double angle, double t0, double t1);
  /// The torque the held frame puts on the rod at state s (N·m, world frame): what the hand at a
  /// hub turns it with (haptics/hub_device.hpp feeds its part about the shaft back to the stylus).
  Vec3 torqueOnRod(const SceneState& s) const;

 private:
  void init(const Scene& scene) override;
  /// The energy at s; with forces != nullptr the torque added into B, with body_torque != nullptr
  /// that torque (the end segment's body frame) written there.
  double term(const SceneState& s, VecX* forces, Vec3* body_torque = nullptr) const;
  /// (direction, roll) at time t.
  std::pair<Vec3, double> poseAt(double t) const;

  End end_;
  std::vector<Keyframe> keyframes_;
  bool turned_ = false;  // the keyframes are the hand's (turn), not the scene's path
  const FramedChain* chain_ = nullptr;
  int segment_ = 0;                     // the end segment
  Eigen::Quaterniond initial_ = Eigen::Quaterniond::Identity();  // its initial frame R₀
  Vec3 stiffness_ = Vec3::Zero();       // B / ℓ
  Vec3 rest_ = Vec3::Zero();            // φ̄
};

}  // namespace filum::mechanics
