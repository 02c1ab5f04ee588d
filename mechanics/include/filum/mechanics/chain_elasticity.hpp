// ChainElasticity: the elastic energy of a FramedChain, a discrete Cosserat rod (Spillmann &
// Teschner 2007; Gazzola et al. 2018) with frames at the nodes. Per segment i (nodes i, i + 1,
// rest length l, edge e = x_{i+1} − x_i, tangent t = e/|e|, material axes d3 = R e3):
//   stretching  E_s = ½ (E A / l) (|e| − l)²,
//   shear       E_a = ¼ κ G A l (|d3_i − t|² + |d3_{i+1} − t|²)   (each end frame held to the
//               segment's tangent: the Cosserat shear strain d3 − t, κ = 0.9 for a disc),
//   bend/twist  E_b = ½ φᵀ B φ / l,   φ = log(R_iᵀ R_{i+1}),   B = diag(E I, E I, G J),
// with A = π r², I = π r⁴/4, J = 2I and G = E / (2 (1 + ν)). Forces on the points are −∂E/∂x;
// torques on the frames (body frame, for the right increment R ← R exp(δ)) are
//   from a term g·d3:     τ = −e3 × (Rᵀ g),
//   from φ at node i + 1: τ = −J_r⁻¹(φ)ᵀ B φ / l,   at node i: τ = +J_l⁻¹(φ)ᵀ B φ / l
// (geometry/rotation_vector.hpp). The energy is invariant under rigid motions, so momentum and
// angular momentum are conserved; tests/mechanics/framed_chain_test.cpp checks the torsion
// frequency, energy and angular momentum converging at second order (RK4 with its orientation
// update, runge_kutta4.cpp) and momentum to round-off. No Jacobian: explicit steps.
#pragma once

#include <memory>

#include "filum/core/force_field.hpp"
#include "filum/core/params.hpp"

namespace filum::mechanics {

class FramedChain;

class ChainElasticity final : public ForceField {
 public:
  /// youngs_modulus E (Pa) > 0; poisson_ratio ν in [0, 0.5] (G = E / (2 (1 + ν))).
  ChainElasticity(double youngs_modulus, double poisson_ratio)
      : youngs_modulus_(youngs_modulus), poisson_ratio_(poisson_ratio) {}
  /// "youngs_modulus": Pa; "poisson_ratio": default 0.5 (incompressible, as soft tissue and
  /// polymers roughly are).
  static std::unique_ptr<ChainElasticity> fromParams(const Params& p);

  std::string typeName() const override { return "ChainElasticity"; }
  void addForce(const SceneState& s, VecX& B) const override;
  double potentialEnergy(const SceneState& s) const override;

  /// E A, κ G A, and B = diag(E I, E I, G J) (SI).
  double axialStiffness() const { return axial_; }
  double shearStiffness() const { return shear_; }
  const Vec3& bendingTwistingStiffness() const { return bending_; }

 private:
  void init(const Scene& scene) override;
  /// Energy of segment i at s, and with forces != nullptr its forces and torques added into B.
  double segment(const SceneState& s, int i, VecX* forces) const;

  double youngs_modulus_, poisson_ratio_;
  const FramedChain* chain_ = nullptr;
  double axial_ = 0.0, shear_ = 0.0;
  Vec3 bending_ = Vec3::Zero();
};

}  // namespace filum::mechanics
