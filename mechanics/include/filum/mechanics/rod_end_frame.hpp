// RodEndFrame: an end of a FramedChain built in — its material frame held at a given direction
// and roll (a cantilever's clamp, the hub of a catheter held by the hand). The rod's own bending
// and twist join the held frame R_h, at the end node, to the end segment's frame R_e, whose
// centre lies half a segment further in:
//   E = ½ φᵀ B φ / ℓ,   φ = log(R_hᵀ R_0) at the start (log(R_eᵀ R_h) at the far end),
//   ℓ = l_e / 2,  B = diag(E I, E I, G J) of the body's ChainElasticity,
// the same term ChainElasticity puts at every interior node, over the end node's half segment.
// So the curvature reaches the end: holding only the first segment's direction (ClampConstraint
// on the polyline's tangent) leaves half a segment rigid at the clamp, a first-order error in the
// segment length (a cantilever's tip deflection 3 l / 2L short: 7.5 % at 21 nodes); with the
// half-segment joint the rod converges at second order (tests/mechanics/rod_mechanics_test.cpp).
// Torques on the end frame (body frame, right increments): −J_r⁻¹(φ)ᵀ B φ / ℓ at the start,
// +J_l⁻¹(φ)ᵀ B φ / ℓ at the far end (chain_elasticity.hpp). The end's position is held
// separately, by a FixedPointConstraint (or any point constraint) at the same abscissa. The
// body's ChainElasticity must come before this component in the scene file.
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <optional>

#include "filum/core/force_field.hpp"
#include "filum/core/params.hpp"

namespace filum::mechanics {

class FramedChain;

class RodEndFrame final : public ForceField {
 public:
  enum class End { kStart, kFinish };
  /// direction: d3 of the held frame (non-zero; nullopt: the end segment's initial tangent);
  /// roll: the held frame's turn about it (rad) from the rod's initial frame turned to it.
  RodEndFrame(End end, std::optional<Vec3> direction, double roll)
      : end_(end), direction_(direction), roll_(roll) {}
  /// "end": "start" (default, s = 0) or "end" (s = 1); "direction": [x, y, z] (default: the
  /// end segment's initial tangent); "roll": rad (default 0).
  static std::unique_ptr<RodEndFrame> fromParams(const Params& p);

  std::string typeName() const override { return "RodEndFrame"; }
  void addForce(const SceneState& s, VecX& B) const override;
  double potentialEnergy(const SceneState& s) const override;

  const Eigen::Quaterniond& heldFrame() const { return held_; }

 private:
  void init(const Scene& scene) override;
  /// φ, the end segment and B φ / ℓ at s.
  double term(const SceneState& s, VecX* forces) const;

  End end_;
  std::optional<Vec3> direction_;
  double roll_;
  const FramedChain* chain_ = nullptr;
  Eigen::Quaterniond held_ = Eigen::Quaterniond::Identity();
  Vec3 stiffness_ = Vec3::Zero();  // B / ℓ
};

}  // namespace filum::mechanics
