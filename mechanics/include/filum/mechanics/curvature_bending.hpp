// CurvatureBending: the exact bending energy of an inextensible-or-not thread with a straight
// natural shape (Kirchhoff rod without twist; docs/architecture.md, "Numbers that matter"):
//   E = ½ E·I ∫ κ² dℓ = ½ E·I ∫_0^1 κ(s)² |P'(s)| ds,   κ = |P' × P''| / |P'|³,
// so with x = P'(s), y = P''(s), C = |x × y|² = |x|²|y|² − (x·y)² and r = |x|²:
//   e(x, y) = ½ E·I C r^(−5/2)  per unit of s.
// Its stiffness is not constant (unlike ParametricBending): gradient and Hessian in (x, y),
//   ∂C/∂x = 2(|y|² x − (x·y) y),  ∂C/∂y = 2(|x|² y − (x·y) x),
//   ∂²C/∂x² = 2(|y|² I − y yᵀ),  ∂²C/∂y² = 2(|x|² I − x xᵀ),  ∂²C/∂x∂y = 4 x yᵀ − 2 y xᵀ − 2 (x·y) I,
//   f = r^(−5/2),  ∂f/∂x = −5 r^(−7/2) x,  ∂²f/∂x² = −5 r^(−7/2) I + 35 r^(−9/2) x xᵀ,
// are chained to the control points through x = Σ b'_j q_j and y = Σ b''_j q_j (SupportJacobian).
// Integrated by Gauss-Legendre per piece (the density is rational: the default 2d − 1 nodes are
// not exact; "quadrature_nodes" raises it). I = π r⁴/4.
#pragma once

#include <memory>
#include <vector>

#include "filum/core/force_field.hpp"
#include "filum/mechanics/curve_quadrature.hpp"
#include "filum/mechanics/elastic_parameters.hpp"
#include "filum/mechanics/support_hessian_cache.hpp"

namespace filum::mechanics {

class CurvatureBending final : public ForceField {
 public:
  /// youngs_modulus (Pa) > 0; quadrature_nodes per piece (0: 2d − 1).
  CurvatureBending(double youngs_modulus, int quadrature_nodes)
      : youngs_modulus_(youngs_modulus), quadrature_nodes_(quadrature_nodes) {}
  /// "youngs_modulus": Pa, "quadrature_nodes": per piece.
  static std::unique_ptr<CurvatureBending> fromParams(const Params& p);

  std::string typeName() const override { return "CurvatureBending"; }
  void addForce(const SceneState& s, VecX& B) const override;
  double potentialEnergy(const SceneState& s) const override;
  void addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const override;
  bool hasJacobian() const override { return true; }

  double bendingStiffness() const { return bending_stiffness_; }

 private:
  void init(const Scene& scene) override;

  /// The Hessian ∇²E of one piece at q: its count (count + 1) / 2 blocks (a, b <= a) into blocks.
  template <int Count>
  void pieceHessian(const QuadraturePiece& piece, const ConstPointsMap& q, Eigen::Matrix3d* blocks) const;

  double youngs_modulus_;
  int quadrature_nodes_;
  double bending_stiffness_ = 0.0;  // E I (N·m²)
  CurveQuadrature quadrature_;
  mutable SupportHessianCache hessian_;  // ∇²E at the last positions asked (see addJacobian)
};

}  // namespace filum::mechanics
