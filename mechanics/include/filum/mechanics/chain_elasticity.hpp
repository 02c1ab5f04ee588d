// ChainElasticity: the elastic energy of a FramedChain, a discrete Cosserat rod with frames on
// its segments (Gazzola et al. 2018). Per segment i (nodes i, i + 1, rest length l_i, edge
// e = x_{i+1} − x_i, tangent t = e/|e|, material axes d3 = R_i e3):
//   stretching  E_s = ½ (E A / l_i) (|e| − l_i)²,
//   shear       E_a = ½ κ G A l_i |d3_i − t_i|²   (the segment's frame held to its own edge: the
//               Cosserat shear strain, 2 (1 − cos γ) ≈ γ² for a shear angle γ; κ(ν, r_in/r) is
//               Cowper's shear coefficient of a disc or a tube, 0.9 for a disc at ν = ½),
// and per interior node j (between segments j − 1 and j, Voronoi length ℓ_j = (l_{j−1} + l_j)/2):
//   bend/twist  E_b = ½ φᵀ B φ / ℓ_j,   φ = log(R_{j−1}ᵀ R_j),   B = diag(E I, E I, G J),
// so that a tangent turning by θ = κ ℓ at a node costs ½ E I κ² ℓ, the Kirchhoff rod's energy of
// curvature κ over the node's length; A, I the section's (FramedChain::Section: a disc,
// A = π r², I = π r⁴/4, or a tube's wall, A = π (r² − r_in²), I = π (r⁴ − r_in⁴)/4), J = 2I and
// G = E / (2 (1 + ν)).
// A rest shape (a J-tip, an angled tip, a coil's helix) replaces φ by φ − φ̄_j: the rest turn
// φ̄_j = ∫ κ̄(s) ds over the node's Voronoi cell [s_j − l_{j−1}/2, s_j + l_j/2] of a rest Darboux
// vector κ̄ = (κ1, κ2, τ) given in the material frame by abscissa spans (integrated exactly, so
// that a span's end between nodes costs no order of accuracy), or the initial shape's own turns
// log(R̄_{j−1}ᵀ R̄_j) ("rest_shape": "initial"). Material may change along the rod: E, ν per
// segment from spans, and the radius per segment from the FramedChain; a node between two
// segments takes their stiffnesses in series, B_j = ℓ_j / (l_{j−1}/(2 B_{j−1}) + l_j/(2 B_j)).
// Forces on the points are −∂E/∂x; torques on the frames (body frame, for the right increment
// R ← R exp(δ)) are
//   from a term g·d3:     τ = −e3 × (Rᵀ g),
//   from φ at frame j:    τ = −J_r⁻¹(φ)ᵀ m,   at frame j − 1: τ = +J_l⁻¹(φ)ᵀ m,   m = B (φ − φ̄) / ℓ
// (geometry/rotation_vector.hpp). The energy is invariant under rigid motions, so momentum and
// angular momentum are conserved. tests/mechanics/framed_chain_test.cpp checks the forces against
// the energy's gradient, the torsion frequency and the invariants;
// tests/mechanics/rod_mechanics_test.cpp the cantilever, the elastica (against shooting
// solutions of Kirchhoff's equations), torsion and the first bending frequency.
//
// Jacobian (implicit steps), K = −H with H the energy's Hessian over the points and the frames'
// right increments δ (R ← R exp(δ)). Per segment, with r = |e|, P = I − t tᵀ, k_s = κGA l and
// E_a = k_s (1 − d3 · t) (equal to ½ k_s |d3 − t|² for unit vectors):
//   H_ee = (E A / l) [t tᵀ + (1 − l / r) P] + k_s [(P d3) tᵀ + t (P d3)ᵀ + (t · d3) P] / r²,
//   H_eδ = k_s P R ê3 / r,   H_δδ = k_s [(t_b · e3) I − ½ (t_b e3ᵀ + e3 t_bᵀ)],  t_b = Rᵀ t,
// (e = x_{i+1} − x_i: ±H_ee on the points, ±H_eδ between points and frame) — exact. Per node, the
// Gauss–Newton part of the bending and twist term, with φ ≈ φ₀ + J_r⁻¹ δ_j − J_l⁻¹ δ_{j−1}:
//   H_jj = J_r⁻ᵀ B̃ J_r⁻¹,  H_{j−1,j−1} = J_l⁻ᵀ B̃ J_l⁻¹,  H_{j−1,j} = −J_l⁻ᵀ B̃ J_r⁻¹,  B̃ = B_j / ℓ_j;
// the term it leaves out is m · ∂²φ, of the order of the moment m = B̃ (φ − φ̄) (zero at rest
// shape, small against B̃ where the turns are small), which costs the Newton iteration a little
// contraction, not accuracy (its residual is exact). The matrix is the symmetric part of ∂Q/∂w:
// the right increments' Lie bracket adds a skew ½ τ̂ that the step matrix symmetrises away.
#pragma once

#include <memory>
#include <vector>

#include "filum/core/force_field.hpp"
#include "filum/core/params.hpp"

namespace filum::mechanics {

class FramedChain;

class ChainElasticity final : public ForceField {
 public:
  /// The material of a span of the rod, s ∈ [from, to] (segments by their middle, nodes' rest
  /// turns by the part of their cell inside).
  struct Span {
    double from = 0.0, to = 1.0;
    double youngs_modulus = 0.0;  // Pa
    double poisson_ratio = 0.5;
    Vec3 rest_curvature = Vec3::Zero();  // (κ1, κ2, τ), rad/m, material frame
  };
  /// The whole rod: youngs_modulus E (Pa) > 0; poisson_ratio ν in [0, 0.5] (G = E / (2 (1 + ν))).
  ChainElasticity(double youngs_modulus, double poisson_ratio)
      : ChainElasticity(std::vector<Span>{Span{0.0, 1.0, youngs_modulus, poisson_ratio, Vec3::Zero()}}, false) {}
  /// spans.front() covers [0, 1] (the defaults); later spans override it where they lie.
  /// rest_from_initial: the rest turns are the initial shape's.
  ChainElasticity(std::vector<Span> spans, bool rest_from_initial)
      : spans_(std::move(spans)), rest_from_initial_(rest_from_initial) {}
  /// "youngs_modulus": Pa; "poisson_ratio": default 0.5 (incompressible, as soft tissue and
  /// polymers roughly are); "rest_curvature": [κ1, κ2] (rad/m, about d1 and d2: a rod bent in
  /// the plane of d3 and d1 turns about d2) and "rest_twist": τ (rad/m) (default 0: straight);
  /// "spans": [{"from": s0, "to": s1, and any of the four above}, ...]; "rest_shape":
  /// "straight" (default: the curvature above) or "initial" (the nodes as given are the rest
  /// shape; no rest_curvature then).
  static std::unique_ptr<ChainElasticity> fromParams(const Params& p);

  std::string typeName() const override { return "ChainElasticity"; }
  void addForce(const SceneState& s, VecX& B) const override;
  double potentialEnergy(const SceneState& s) const override;
  void addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const override;
  bool hasJacobian() const override { return true; }

  /// Segment i's E A, κ G A, and B = diag(E I, E I, G J) (SI).
  double axialStiffness(int segment) const { return axial_[segment]; }
  double shearStiffness(int segment) const { return shear_[segment]; }
  const Vec3& bendingTwistingStiffness(int segment) const { return bending_[segment]; }
  /// ∫ κ̄ ds over s ∈ [a, b] (rest arc lengths, m): the rest turn between two material frames.
  Vec3 restTurn(double a, double b) const;
  bool restFromInitial() const { return rest_from_initial_; }

 private:
  void init(const Scene& scene) override;
  /// The span holding abscissa s (the last one listed that does).
  const Span& spanAt(double s) const;
  /// Stretching and shear energy of segment i at s; with forces != nullptr its forces and
  /// torques added into B.
  double segment(const SceneState& s, int i, VecX* forces) const;
  /// Bending and twist energy at interior node j (between the frames of segments j − 1 and j);
  /// with forces != nullptr its torques added into B.
  double joint(const SceneState& s, int j, VecX* forces) const;

  std::vector<Span> spans_;
  bool rest_from_initial_;
  const FramedChain* chain_ = nullptr;
  double length_ = 0.0;                                        // the rod's rest length (m)
  std::vector<double> axial_, shear_;                          // per segment
  std::vector<Vec3> bending_;                                  // per segment
  std::vector<Vec3> joint_bending_, joint_rest_;               // per node: B_j / ℓ_j and φ̄_j
};

}  // namespace filum::mechanics
