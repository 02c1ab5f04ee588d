// SpringForceField: the paper's discrete deformation energy (§3 "Deformation Energy", Fig. 1,
// after Provot): K points x_k = P(s_k) sampled at equal parametric spacing, stretch springs
// between neighbours (k, k+1) and bend springs between next neighbours (k, k+2), rest lengths
// taken from the initial curve. Spring force on the pair (a, b), u = (x_b − x_a)/l:
//   f = [k (l − l0) + c (v_b − v_a)·u] u,  F_a += f, F_b −= f,
// mapped to the control points by Q_i += Σ_k b_i(s_k) F_k (BodyPoint::applyJT).
//
// Jacobian. With d = x_b − x_a, P = I − u uᵀ and Δv = v_b − v_a, the pair force f(d, Δv) has
//   G = ∂f/∂d = k u uᵀ + (k (l − l0) + c Δv·u) P / l + c u Δvᵀ P / l,   G_v = ∂f/∂Δv = c u uᵀ,
// and ∂F_a/∂x_b = G, ∂F_a/∂x_a = −G, ∂F_b/∂x_a = G, ∂F_b/∂x_b = −G (same with G_v for
// velocities), mapped to control points as ∂Q_i/∂q_j = Σ_{k,m} b_i(s_k) b_j(s_m) ∂F_k/∂x_m.
// The dashpot's position term c u Δvᵀ P / l is not symmetric (a dissipative force).
// On a cut curve (CurveBody::cut) only samples of one strand are joined by springs.
#pragma once

#include <memory>
#include <vector>

#include "filum/core/body_point.hpp"
#include "filum/core/force_field.hpp"
#include "filum/core/params.hpp"

namespace filum::mechanics {

class SpringForceField final : public ForceField {
 public:
  /// stretch_stiffness (N/m) > 0, bend_stiffness (N/m) >= 0, damping (N·s/m) >= 0,
  /// samples >= 3 points along the curve (0: twice the control points).
  SpringForceField(double stretch_stiffness, double bend_stiffness, double damping, int samples);
  static std::unique_ptr<SpringForceField> fromParams(const Params& p);

  std::string typeName() const override { return "SpringForceField"; }
  void addForce(const SceneState& s, VecX& B) const override;
  double potentialEnergy(const SceneState& s) const override;
  void addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const override;
  bool hasJacobian() const override { return true; }

  int sampleCount() const { return samples_; }

 private:
  struct Spring {
    int a, b;          // sample indices
    double stiffness;  // N/m
    double rest;       // m
  };
  void init(const Scene& scene) override;

  double stretch_stiffness_, bend_stiffness_, damping_;
  int samples_;
  /// x_k = P(s_k) and ẋ_k of every sample, through its point's mapping.
  void sample(ConstPointsRef q, Points& x) const;
  void sampleVelocities(ConstPointsRef q, ConstPointsRef v, Points& out) const;

  std::vector<BodyPoint> ends_;  // the samples s_k, uniform on [0, 1]: the springs' end points
  std::vector<Spring> springs_;
  mutable Points x_, v_, f_;  // workspace: sample positions, velocities, forces
};

}  // namespace filum::mechanics
