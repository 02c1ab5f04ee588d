// PointLoad: a force and a torque applied at one abscissa of a curve body — a weight hung on a
// rod's tip, an instrument pushing on a thread, the end load of the elastica. The force F (N,
// world frame) acts on the material point P(s); its generalized force on the control points is
// the mapping's transpose,
//   Q_j += b_j(s) F                  (P(s) = Σ_j b_j(s) q_j, CurveBody),
// and the torque τ (N·m, world frame) acts on the material frame that holds s, for bodies with
// frames (CurveBody::addTorque; a FramedChain's segment: Q_ω += Rᵀ τ, the power τ · R ω).
// Constant, or following a path over time: keyframes (time, force, torque), linear in between,
// held before the first and after the last.
//
// Potential energy: −F(t) · P(s), the work of the force (a constant force is conservative); a
// torque's work is not counted (a torque has no potential on a rotating frame in general).
#pragma once

#include <memory>
#include <vector>

#include "filum/core/body_point.hpp"
#include "filum/core/force_field.hpp"
#include "filum/core/params.hpp"

namespace filum {
class CurveBody;
}

namespace filum::mechanics {

class PointLoad final : public ForceField {
 public:
  struct Keyframe {
    double time = 0.0;       // s
    Vec3 force = Vec3::Zero();   // N, world frame
    Vec3 torque = Vec3::Zero();  // N·m, world frame
  };
  /// abscissa s in [0, 1]; keyframes with strictly increasing times (one: constant).
  PointLoad(double abscissa, std::vector<Keyframe> keyframes);
  /// "abscissa": s in [0, 1]; either "force": [N] and/or "torque": [N·m] (constant), or
  /// "path": [{"time": s, "force": [...], "torque": [...]}, ...] (times increasing, force and
  /// torque default to zero).
  static std::unique_ptr<PointLoad> fromParams(const Params& p);

  std::string typeName() const override { return "PointLoad"; }
  void addForce(const SceneState& s, VecX& B) const override;
  double potentialEnergy(const SceneState& s) const override;
  /// The force does not depend on the configuration (a fixed direction at a material point):
  /// ∂Q/∂q = 0, ∂Q/∂q̇ = 0, nothing to add. (A torque on a frame, Rᵀτ, does depend on R, but
  /// bodies with frames take explicit steps only.)
  void addJacobian(const SceneState&, double, double, JacobianAccumulator&) const override {}
  bool hasJacobian() const override { return true; }
  bool jacobianIsConstant() const override { return true; }

  /// The force and the torque at time t (linear between keyframes).
  Keyframe loadAt(double t) const;
  double abscissa() const { return abscissa_; }
  /// Its point, while it loads it.
  void actingAbscissas(const SceneState& s, std::vector<double>& out) const override {
    const Keyframe load = loadAt(s.time);
    if (load.force != Vec3::Zero() || load.torque != Vec3::Zero()) out.push_back(abscissa_);
  }

 private:
  void init(const Scene& scene) override;

  double abscissa_;
  std::vector<Keyframe> keyframes_;
  const CurveBody* curve_ = nullptr;
  BodyPoint point_;  // the loaded point: its force goes up through it
};

}  // namespace filum::mechanics
