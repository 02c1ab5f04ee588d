// The mouse probe of `filum view`, the stand-in for a haptic device: a sphere the user drags
// through the scene that pushes the threads, or grabs one and pulls it.
//   push: every point x_k = P(s_k) sampled along a spline (SplineAxisMapping) that enters the
//         sphere (centre c, radius R = probe radius + thread radius) is pushed out by a penalty
//         F_k = k_p (R − d) n,  d = |x_k − c|,  n = (x_k − c)/d,  mapped up Q += Wᵀ F;
//   grab: a spring–damper to the point of the thread nearest to the probe when the grab starts
//         (s* = geometry::closestPoint): F = k_g (X − P(s*)) − c_g Ṗ(s*), Q_i += b_i(s*) F — a
//         soft FixedPointConstraint whose target is the mouse.
// Stiffnesses default to the stiffest an explicit step allows: with the effective mass of the
// curve point m_eff(s) = 1 / (bᵀ M⁻¹ b), k = (ω dt)² m_eff / dt² with ω dt = 0.3 (push) and
// 0.5 (grab), well inside RK4's stability limit (2.8); c_g = 2 sqrt(k_g m_eff) (critical).
// Both forces have analytic Jacobians (implicit integrators):
//   push: ∂F/∂x = k_p [ −n nᵀ + (R − d)/d (I − n nᵀ) ],   grab: K = −k_g b bᵀ ⊗ I, D = −c_g b bᵀ ⊗ I.
#pragma once

#include <limits>
#include <memory>

#include "filum/core/force_field.hpp"
#include "filum/core/scene.hpp"
#include "filum/visual/spline_axis_mapping.hpp"
#include "filum/visual/visual_model.hpp"

namespace filum::visual {

/// What the mouse sets and the probe's force fields read (one per scene, shared).
struct ProbeState {
  Vec3 position = Vec3::Zero();  // centre X of the sphere (m)
  double radius = 1e-3;          // m
  bool touching = false;         // the sphere is in the scene and pushes (a mouse button is held)
  bool grabbing = false;         // a point of a thread is held
  const MechanicalState* grab_body = nullptr;
  double grab_abscissa = 0.0;
  double push_stiffness = std::numeric_limits<double>::infinity();  // N/m, capped for stability
  double grab_stiffness = std::numeric_limits<double>::infinity();  // N/m, capped for stability
};

/// Starts a grab of the spline point nearest to the probe centre, if one lies within `capture`
/// (m) of it; returns whether a point was grabbed. Uses the scene's current state.
bool startGrab(ProbeState& probe, const Scene& scene, double capture);

/// The probe's forces on one curve body (added to every curve body by `filum view`, not a
/// scene-file component).
class ProbeForceField final : public ForceField {
 public:
  /// samples: points along the curve tested against the sphere (0: 4 per control point).
  ProbeForceField(std::shared_ptr<const ProbeState> probe, int samples = 0);

  std::string typeName() const override { return "MouseProbe"; }
  void addForce(const SceneState& s, VecX& B) const override;
  double potentialEnergy(const SceneState& s) const override;
  void addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const override;
  bool hasJacobian() const override { return true; }

  /// Effective mass 1 / (bᵀ M⁻¹ b) of the curve point at abscissa s (kg).
  double effectiveMass(double s) const;
  /// The stiffnesses and damping in use (after the stability caps).
  double pushStiffness() const;
  double grabStiffness() const;
  double grabDamping() const;

 protected:
  void init(const Scene& scene) override;

 private:
  bool grabbing() const { return probe_->grabbing && probe_->grab_body == &body(); }
  std::shared_ptr<const ProbeState> probe_;
  int samples_;
  double dt_ = 1e-4, thread_radius_ = 0.0, sample_mass_ = 0.0;
  std::unique_ptr<SplineAxisMapping> mapping_;
  mutable Points x_, f_;  // workspace: sample positions and forces
  mutable Points unit_load_, response_;  // workspace of effectiveMass: b and M⁻¹ b
  mutable double mass_abscissa_ = 0.0, mass_at_abscissa_ = 0.0;  // its last answer
};

/// The probe's sphere as a visual model: drawn while the mouse button is held, red when it
/// pushes, green when it holds a point.
class ProbeVisual final : public VisualModel {
 public:
  explicit ProbeVisual(std::shared_ptr<const ProbeState> probe);
  std::string typeName() const override { return "ProbeVisual"; }
  bool needsBody() const override { return false; }
  void update(const SceneState& s) override;
  const TriangleMesh& mesh(int = 0) const override { return mesh_; }

 private:
  std::shared_ptr<const ProbeState> probe_;
  TriangleMesh unit_, mesh_;
};

}  // namespace filum::visual
