// The interaction tool: a sphere at the stylus (or the mouse) that pushes the threads, and the
// grasper's jaws that hold one where they close — the paper's "virtual probe, via the Phantom ...
// the white cylinder linking the user to the curve" (Lenoir et al., §5, Fig. 1a).
//   push:  every sample x_k = P(s_k) of a curve body inside the sphere (centre X, radius
//          R = tool radius + r(s_k), the thread's radius there) is pushed out by a penalty
//            F_k = k_p (R − d) n,  d = |x_k − X|,  n = (x_k − X)/d,  Q += Σ_k b(s_k) F_k;
//   grasp: the virtual coupling between the stylus X, Ẋ and the held point P(s*), Ṗ(s*)
//          (coupling.hpp):  F = k (X − P) + c (Ẋ − Ṗ),  Q_i += b_i(s*) F.
// The grasped point is the simulated tool: the jaws hold P(s*) rigidly and have no mass of their
// own, so the thread's mass at s* is the tool's, and the spring k, c is the coupling the hand
// feels through (toolForce), never the thread's own constraint force (which would not be passive).
//
// Stiffnesses: an explicit step is stable only below (ω dt)² m_eff / dt², with m_eff(s) =
// 1 / (bᵀ M⁻¹ b) the effective mass of the curve point, ω dt = 0.3 (push) and 0.5 (grasp), so
// there they are capped; an implicit step takes the gains as set. An unset stiffness (infinite)
// is that cap either way, and an unset grasp damping (negative) is critical, c = 2 sqrt(k m_eff).
// The tool moves on during a step: the fields see X(t) = X + Ẋ (t − t_sample), the stylus
// extrapolated at its sampled velocity to the time of each evaluation (the end of an implicit
// step). Holding X still over the step instead would leave the thread a step behind the hand
// and make the hand feel a false damping k·dt (0.9 N·s/m for a Touch's coupling at 1 ms, ten
// times the coupling's own) whenever it moves.
// Both forces have analytic Jacobians (implicit integrators):
//   push: ∂F_k/∂x_k = k_p [ −n nᵀ + (R − d)/d (I − n nᵀ) ],   grasp: K = −k b bᵀ ⊗ I, D = −c b bᵀ ⊗ I.
#pragma once

#include <limits>
#include <memory>
#include <vector>

#include "filum/core/body_point.hpp"
#include "filum/core/force_field.hpp"
#include "filum/core/scene.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::haptics {

/// What the device (or the mouse) sets between steps and the tool's force fields read.
struct ToolState {
  Vec3 position = Vec3::Zero();  // X at `time`, centre of the sphere (m)
  Vec3 velocity = Vec3::Zero();  // Ẋ (m/s)
  double time = 0.0;             // simulated time the stylus sample belongs to (s)
  double radius = 1e-3;          // m
  bool touching = false;         // the sphere is in the scene and pushes
  bool grasping = false;         // the jaws hold a point
  BodyPoint grasp;               // the held point s* of a curve body (attached while grasping)
  double push_stiffness = std::numeric_limits<double>::infinity();   // N/m (infinite: the cap)
  double grasp_stiffness = std::numeric_limits<double>::infinity();  // k, N/m (infinite: the cap)
  double grasp_damping = -1.0;   // c, N·s/m (negative: critical)
};

/// Closes the jaws on the curve point nearest to the tool centre, if one lies within `capture`
/// (m) of it, in the scene's current state; returns whether a point is held.
bool startGrasp(ToolState& tool, const Scene& scene, double capture);
/// Holds the point at abscissa s of `body` (an attachment: a thread's end to the stylus).
void grasp(ToolState& tool, const CurveBody& body, double abscissa);
void release(ToolState& tool);
/// X(t) = X + Ẋ (t − t_sample).
inline Vec3 toolPosition(const ToolState& tool, double t) { return tool.position + tool.velocity * (t - tool.time); }

/// The force the bodies exert on the tool and its Jacobians with respect to the tool's position
/// and velocity (the local linear model of the servo loop, local_linear_model.hpp).
struct ToolReaction {
  Vec3 force = Vec3::Zero();                            // N
  Eigen::Matrix3d stiffness = Eigen::Matrix3d::Zero();  // ∂F/∂X, N/m
  Eigen::Matrix3d damping = Eigen::Matrix3d::Zero();    // ∂F/∂Ẋ, N·s/m
};

/// The tool's forces on one curve body (added to a scene's curve bodies by whoever drives the
/// tool: `filum view`'s mouse, a HapticSession; not a scene-file component).
class ToolForceField final : public ForceField {
 public:
  /// samples: points along the curve tested against the sphere (0: 4 per control point, >= 8).
  explicit ToolForceField(std::shared_ptr<const ToolState> tool, int samples = 0);

  std::string typeName() const override { return "InteractionTool"; }
  void addForce(const SceneState& s, VecX& B) const override;
  double potentialEnergy(const SceneState& s) const override;
  void addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const override;
  bool hasJacobian() const override { return true; }

  /// Adds this body's reaction on the tool at state s (the opposite of the forces above).
  void addReaction(const SceneState& s, ToolReaction& out) const;

  /// Effective mass 1 / (bᵀ M⁻¹ b) of the curve point at abscissa s (kg).
  double effectiveMass(double s) const;
  /// The gains in use (after the caps).
  double pushStiffness() const;
  double graspStiffness() const;
  double graspDamping() const;

 protected:
  void init(const Scene& scene) override;

 private:
  bool grasping() const { return tool_->grasping && tool_->grasp.body() == body().curve(); }
  bool pushing() const { return tool_->touching && !grasping(); }
  /// The held point, while the jaws (or the stylus) hold this body.
  void actingAbscissas(const SceneState&, std::vector<double>& out) const override {
    if (grasping()) out.push_back(tool_->grasp.abscissa());
  }
  /// The stiffness to use: capped for explicit steps, the cap when unset.
  double gain(double requested, double cap) const;
  /// P(s*) and Ṗ(s*) at state s.
  void graspPoint(const SceneState& s, Vec3& P, Vec3& V) const;
  /// One sample of the push inside the sphere: its point s_k, its distance d to the centre
  /// (0 < d < R), the unit normal n out of the sphere; k the push stiffness.
  struct Overlap {
    const BodyPoint& point;
    double distance, radius, stiffness;
    Vec3 normal;
    double depth() const { return radius - distance; }
    /// F_k = k (R − d) n and ∂F_k/∂x_k = k [ −n nᵀ + (R − d)/d (I − n nᵀ) ].
    Vec3 force() const { return stiffness * depth() * normal; }
    Eigen::Matrix3d jacobian() const;
  };
  /// Calls visit(Overlap) for every push sample inside the sphere at state s.
  template <typename Visit>
  void forEachOverlap(const SceneState& s, Visit visit) const;
  std::shared_ptr<const ToolState> tool_;
  int samples_;
  double dt_ = 1e-4, sample_mass_ = 0.0;
  bool explicit_step_ = true;
  std::vector<BodyPoint> push_points_;  // the push samples (fixed abscissas s_k)
  std::vector<double> sample_radii_;    // the thread's radius r(s_k) at each
  mutable Points unit_load_, response_;          // workspace of effectiveMass: b and M⁻¹ b
  mutable double mass_abscissa_ = 0.0, mass_at_abscissa_ = 0.0;  // its last answer
};

}  // namespace filum::haptics
