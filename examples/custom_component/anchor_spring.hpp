// AnchorSpring: the application's own force field, a zero-length spring of stiffness k between the
// material point P(s) of a curve body and a fixed anchor A — a finger, a magnet or a stay suture
// holding one point of a thread. With P(s) = Σ_j b_j(s) q_j (the body's basis row at s):
//   energy     E = ½ k |P(s) − A|²
//   force      F = −k (P(s) − A) on the material point, i.e. Q_j = b_j(s) F on control point j
//   Jacobian   ∂Q_i/∂q_j = −k b_i(s) b_j(s) I₃ (constant), ∂Q/∂q̇ = 0
// The point is a filum::BodyPoint, the mapping of one point of the body: P(s) goes down through
// it (map) and F goes up through it (addForce, its applyJT), as every force at a point does.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "filum/core/body_point.hpp"
#include "filum/core/force_field.hpp"
#include "filum/core/mechanical_state.hpp"
#include "filum/core/params.hpp"
#include "filum/core/scene_error.hpp"

namespace custom_component {

class AnchorSpring final : public filum::ForceField {
 public:
  /// stiffness k (N/m) > 0, abscissa s ∈ [0, 1] of the held point, anchor A (m, world frame).
  AnchorSpring(double stiffness, double abscissa, const filum::Vec3& anchor)
      : stiffness_(stiffness), abscissa_(abscissa), anchor_(anchor) {}
  /// Scene-file form: {"type": "AnchorSpring", "stiffness": k, "abscissa": s, "anchor": [x, y, z]}.
  /// Throws filum::SceneError naming the file, the JSON path and the value at fault.
  static std::unique_ptr<AnchorSpring> fromParams(const filum::Params& p) {
    return std::make_unique<AnchorSpring>(p.positive({"stiffness", "N/m"}), p.abscissa("abscissa"), p.vec3({"anchor", "m"}));
  }

  std::string typeName() const override { return "AnchorSpring"; }

  void addForce(const filum::SceneState& s, filum::VecX& B) const override {
    point_.addForce(-stiffness_ * (point_.map(s.q) - anchor_), B);  // Q_j += b_j(s) F
  }

  double potentialEnergy(const filum::SceneState& s) const override {
    return 0.5 * stiffness_ * (point_.map(s.q) - anchor_).squaredNorm();
  }

  /// Adds k_factor·K (D = 0): the blocks −k b_i b_j I₃ over the point's mapping row (global
  /// point numbers and weights b_j(s)).
  void addJacobian(const filum::SceneState&, double k_factor, double /*d_factor*/,
                   filum::JacobianAccumulator& out) const override {
    point_.forEachWeight([&](int i, double b_i) {
      point_.forEachWeight([&](int j, double b_j) { out.addIsotropic(i, j, -k_factor * stiffness_ * b_i * b_j); });
    });
  }
  bool hasJacobian() const override { return true; }
  bool jacobianIsConstant() const override { return true; }

  /// Its point, for adaptive refinement (keeps the curve fine where it is held).
  void actingAbscissas(const filum::SceneState&, std::vector<double>& out) const override {
    out.push_back(abscissa_);
  }

  /// The spring's tension k |P(s) − A| (N) at state s.
  double tension(const filum::SceneState& s) const {
    return stiffness_ * (point_.map(s.q) - anchor_).norm();
  }

 private:
  /// The body is bound by the scene before init: check that it is a curve, and hold the point.
  void init(const filum::Scene&) override {
    const filum::CurveBody* curve = body().curve();
    if (!curve) throw filum::SceneError(origin(), "a curve body for " + describe(), body().describe());
    point_.attach(*curve, abscissa_);
  }

  double stiffness_, abscissa_;
  filum::Vec3 anchor_;
  filum::BodyPoint point_;  // P(s) on the body (its weights follow a refinement of the body)
};

}  // namespace custom_component
