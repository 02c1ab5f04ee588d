// GreenLagrangeStretching: continuous stretching energy of a thread with the Green-Lagrange
// strain (Nocent & Rémion, CAS 2001; [Lenoir talk 2008] "continuous stretching"):
//   ε(s) = (|P'(s)|² − |P0'(s)|²) / (2 |P0'(s)|²),
//   E = ½ ∫_0^1 E·A ε(s)² |P0'(s)| ds            (|P0'| ds = rest arc length dσ),
// E Young's modulus (Pa), A = π r² the cross-section of the body's radius, P0 the rest
// configuration (CurveQuadrature). Integrated by Gauss-Legendre on each polynomial piece
// (2d − 1 nodes per piece make it exact for a uniformly parametrized rest curve).
//
// At a node g with weight w, x = P'(s_g) = Σ_j b'_j q_j, a0 = |P0'(s_g)| and c = E A w / a0:
//   E_g = ½ c a0² ε²,  ∂E_g/∂x = c ε x,  ∂²E_g/∂x² = c (ε I + x xᵀ / a0²),
//   Q_j = −Σ_g b'_j ∂E_g/∂x,  K_ij = ∂Q_i/∂q_j = −Σ_g b'_i b'_j ∂²E_g/∂x².
// The axial force carried by the thread is N = E A ε |P'|/|P0'| (second Piola-Kirchhoff stress
// E ε times the stretch). In compression (ε < 0) the transverse stiffness c ε is negative: a
// string buckles; bending energies restore it.
//
// "jacobian": "definite" drops that negative term from K (c ε replaced by max(c ε, 0); Choi & Ko,
// "Stable but responsive cloth", SIGGRAPH 2002, do the same for compressed springs), so that
// −K is positive semi-definite and an implicit step matrix M − h D − h² K stays positive
// definite. Why it matters for a stiff thread: the compressed term makes M − h²K indefinite as
// soon as |N| h² / ℓ_cp exceeds the mass of a control point m_cp (ℓ_cp the control-point
// spacing) along a direction that bending does not stiffen — for a 2-0 silk suture at h = 1 ms
// and ℓ_cp = 1 mm, |N| > m_cp ℓ_cp / h² ≈ 9e-5 N — and a linearly implicit step then moves the
// thread along that direction without bound (a knot resting on its contacts jumped apart at
// 2.5 m/s within five steps of 1 ms). The force is unchanged: only the step's linearization is,
// so a converged Newton step is the same; the linearized step is Baraff & Witkin's on the
// definite part. Default "exact": the full Hessian.
//
// Rupture: with "break_force" (N), or "tensile_strength" (Pa: the break force σ_u A), the thread
// tears where N first exceeds it (tearsAt: the largest N over the quadrature nodes at the end of a
// step; Scene::step cuts it there before the next).
//
// Stiffness derivative (for RayleighDamping): with ω = Σ_j b'_j w_j at a node,
//   ∂(∂²E_g/∂x² ω)/∂x = (c / a0²) (ω xᵀ + (x·ω) I + x ωᵀ),
//   ∂(K w)_i/∂q_k = −Σ_g b'_i b'_k (c / a0²) (ω xᵀ + (x·ω) I + x ωᵀ).
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <vector>

#include "filum/core/force_field.hpp"
#include "filum/mechanics/curve_quadrature.hpp"
#include "filum/mechanics/elastic_parameters.hpp"
#include "filum/mechanics/support_hessian_cache.hpp"
#include "filum/mechanics/stiffness_derivative.hpp"

namespace filum::mechanics {

class GreenLagrangeStretching final : public ForceField, public StiffnessDerivative {
 public:
  explicit GreenLagrangeStretching(ElasticParameters parameters, bool definite_jacobian = false)
      : parameters_(parameters), definite_jacobian_(definite_jacobian) {}
  /// The tension at which the thread tears (N; infinite: never), or its tensile strength (Pa).
  void setBreakForce(double force) { break_force_ = force; }
  void setTensileStrength(double stress) { tensile_strength_ = stress; }
  double breakForce() const { return break_force_; }
  bool tearsAt(const SceneState& s, double& abscissa, double& tension) const override;
  /// "youngs_modulus": Pa, "rest_length": m (default: the initial curve's arc length),
  /// "quadrature_nodes": per piece (default 2d − 1), "jacobian": "exact" (default) or
  /// "definite" (no negative transverse stiffness in compression, see above).
  static std::unique_ptr<GreenLagrangeStretching> fromParams(const Params& p);

  std::string typeName() const override { return "GreenLagrangeStretching"; }
  void addForce(const SceneState& s, VecX& B) const override;
  double potentialEnergy(const SceneState& s) const override;
  void addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const override;
  bool hasJacobian() const override { return true; }
  void addStiffnessDerivative(const SceneState& s, const VecX& w, double factor, JacobianAccumulator& out) const override;

  /// E·A (N).
  double axialStiffness() const { return axial_stiffness_; }
  /// ℓ0 (m), the rest length integrated by the quadrature.
  double restLength() const { return quadrature_.restLength(); }

 private:
  void init(const Scene& scene) override;

  ElasticParameters parameters_;
  bool definite_jacobian_ = false;
  double axial_stiffness_ = 0.0;  // E A (N)
  double break_force_ = std::numeric_limits<double>::infinity();     // N
  double tensile_strength_ = std::numeric_limits<double>::infinity();  // Pa (sets break_force_ at init)
  std::vector<double> node_abscissas_;  // s_g of the quadrature nodes (tearsAt)
  /// What a force evaluation reads of a quadrature node, packed (the node's BasisRow also holds
  /// values and second derivatives): b'_j, c and a0².
  struct Node {
    std::array<double, geometry::BasisRow::kMaxSupport> d1{};
    double c = 0.0;     // E A w_g / a0_g (N)
    double a0sq = 0.0;  // |P0'(s_g)|²
  };
  /// Σ_g over one piece of −b'_j c ε x into Q (Count > 0: the support size known at compile time).
  template <int Count>
  void addPieceForce(const QuadraturePiece& piece, const double* q, double* Q) const;
  /// addForce for a body whose pieces are all cubic with 5 nodes (cubic_pieces_).
  void addCubicPieceForces(const double* q, double* Q) const;
  /// A piece of 4 points and 5 nodes, packed for fixed-size products.
  struct CubicPiece {
    Eigen::Matrix<double, 5, 4> d1;  // b'_j(s_g)
    Eigen::Matrix<double, 5, 1> c, a0sq, inverse_2a0sq;
    Eigen::Matrix<double, 5, 10> pair_products;  // b'_a b'_b of pair k = a (a + 1) / 2 + b at node g
  };
  std::vector<CubicPiece> cubic_pieces_;  // empty unless every piece is one
  void cubicPieceHessian(const QuadraturePiece& piece, const CubicPiece& cubic, const double* q,
                         Eigen::Matrix3d* blocks) const;
  /// The Hessian ∇²E of one piece at q: its count (count + 1) / 2 blocks (a, b <= a).
  template <int Count>
  void pieceHessian(const QuadraturePiece& piece, const double* q, Eigen::Matrix3d* blocks) const;

  CurveQuadrature quadrature_;
  std::vector<double> c_;         // E A w_g / a0_g per node (N)
  std::vector<Node> nodes_;
  mutable SupportHessianCache hessian_;  // ∇²E at the last positions asked (see addJacobian)
};

}  // namespace filum::mechanics
