// ChainElasticity: the elastic energy of a FramedChain, a discrete Cosserat rod with frames on
// its segments (Gazzola et al. 2018). Per segment i (nodes i, i + 1, rest length l_i, edge
// e = x_{i+1} − x_i, tangent t = e/|e|, material axes d3 = R_i e3):
//   stretching  E_s = ½ (E A / l_i) (|e| − l_i)²,
//   shear       E_a = ½ κ G A l_i |d3_i − t_i|²   (the segment's frame held to its own edge: the
//               Cosserat shear strain, 2 (1 − cos γ) ≈ γ² for a shear angle γ; κ = 0.9, a disc),
// and per interior node j (between segments j − 1 and j, Voronoi length ℓ_j = (l_{j−1} + l_j)/2):
//   bend/twist  E_b = ½ φᵀ B φ / ℓ_j,   φ = log(R_{j−1}ᵀ R_j),   B = diag(E I, E I, G J),
// so that a tangent turning by θ = κ ℓ at a node costs ½ E I κ² ℓ, the Kirchhoff rod's energy of
// curvature κ over the node's length; A = π r², I = π r⁴/4, J = 2I and G = E / (2 (1 + ν)). The
// rest state is straight and untwisted. Forces on the points are −∂E/∂x; torques on the frames
// (body frame, for the right increment R ← R exp(δ)) are
//   from a term g·d3:     τ = −e3 × (Rᵀ g),
//   from φ at frame j:    τ = −J_r⁻¹(φ)ᵀ B φ / ℓ,   at frame j − 1: τ = +J_l⁻¹(φ)ᵀ B φ / ℓ
// (geometry/rotation_vector.hpp). The energy is invariant under rigid motions, so momentum and
// angular momentum are conserved. tests/mechanics/framed_chain_test.cpp checks the forces against
// the energy's gradient, the torsion frequency and the invariants;
// tests/mechanics/rod_mechanics_test.cpp the cantilever, the elastica (against shooting
// solutions of Kirchhoff's equations), torsion and the first bending frequency. No Jacobian:
// explicit steps.
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
  /// Stretching and shear energy of segment i at s; with forces != nullptr its forces and
  /// torques added into B.
  double segment(const SceneState& s, int i, VecX* forces) const;
  /// Bending and twist energy at interior node j (between the frames of segments j − 1 and j);
  /// with forces != nullptr its torques added into B.
  double joint(const SceneState& s, int j, VecX* forces) const;

  double youngs_modulus_, poisson_ratio_;
  const FramedChain* chain_ = nullptr;
  double axial_ = 0.0, shear_ = 0.0;
  Vec3 bending_ = Vec3::Zero();
};

}  // namespace filum::mechanics
