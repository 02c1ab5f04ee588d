// ParametricBending: the quadratic bending energy of a thread (docs/architecture.md, "Numbers that
// matter"; [Lenoir talk 2008]: "continuous bending, approx. using parametric curvature"):
//   E = ½ E·I ∫ |d²P/dσ²|² dσ,   σ the rest arc length,
// which, with d²P/dσ² ≈ P''/|P0'|² (exact for a uniformly parametrized rest curve, |P0'| constant)
// and dσ = |P0'| ds, is
//   E = ½ E·I ∫_0^1 |P''(s)|² / |P0'(s)|³ ds = ½ Σ_α (q^α)ᵀ K_b q^α,
//   (K_b)_ij = E·I ∫ b''_i b''_j / |P0'|³ ds,
// I = π r⁴/4. K_b is constant and banded like the mass matrix (half bandwidth d): precomputed once
// by Gauss-Legendre, Q = −K_b q per coordinate, O(n) per evaluation; the Jacobian is −K_b ⊗ I₃.
// It equals the exact ½ EI ∫ κ² dσ when the thread keeps its parametric speed (stiff stretching)
// and deflections are small; large rotations add the tangential part of P'' (CurvatureBending is
// exact). The natural shape is straight.
#pragma once

#include <memory>

#include "filum/core/force_field.hpp"
#include "filum/mechanics/elastic_parameters.hpp"
#include "filum/mechanics/scalar_band.hpp"
#include "filum/mechanics/stiffness_derivative.hpp"

namespace filum::mechanics {

class ParametricBending final : public ForceField, public StiffnessDerivative {
 public:
  explicit ParametricBending(ElasticParameters parameters) : parameters_(parameters) {}
  /// "youngs_modulus": Pa, "rest_length": m (default: the initial curve's), "quadrature_nodes".
  static std::unique_ptr<ParametricBending> fromParams(const Params& p);

  std::string typeName() const override { return "ParametricBending"; }
  void addForce(const SceneState& s, VecX& B) const override;
  double potentialEnergy(const SceneState& s) const override;
  void addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const override;
  bool jacobianIsConstant() const override { return true; }
  bool hasJacobian() const override { return true; }
  /// K_b is constant: ∂(K w)/∂q = 0.
  void addStiffnessDerivative(const SceneState&, const VecX&, double, JacobianAccumulator&) const override {}

  /// E·I (N·m²).
  double bendingStiffness() const { return bending_stiffness_; }
  /// K_b (n × n, N/m).
  const SparseMatrix& stiffnessMatrix() const { return stiffness_; }

 private:
  void init(const Scene& scene) override;

  ElasticParameters parameters_;
  double bending_stiffness_ = 0.0;
  SparseMatrix stiffness_;  // K_b
  ScalarBand band_;         // K_b as a band, for the force
  mutable Points kq_;       // workspace K_b q
};

}  // namespace filum::mechanics
