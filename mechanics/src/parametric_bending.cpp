#include "filum/mechanics/parametric_bending.hpp"

#include "filum/mechanics/curve_quadrature.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum::mechanics {

std::unique_ptr<ParametricBending> ParametricBending::fromParams(const Params& p) {
  return std::make_unique<ParametricBending>(ElasticParameters::fromParams(p));
}

void ParametricBending::init(const Scene&) {
  const DynamicSpline& spline = splineBody(*this);
  bending_stiffness_ = parameters_.youngs_modulus * secondMomentOfArea(spline.radius());
  const int nodes = parameters_.quadrature_nodes > 0 ? parameters_.quadrature_nodes
                                                     : defaultNodesPerPiece(spline.basis().degree());
  const CurveQuadrature quadrature(spline.basis(), nodes, spline.initialPositions(), parameters_.rest_length);
  // (K_b)_ij = E I Σ_g w_g b''_i b''_j / a0³, each product once and mirrored (exactly symmetric).
  Triplets entries;
  for (const QuadratureNode& node : quadrature.nodes()) {
    const double a0 = node.rest_speed;
    const double c = bending_stiffness_ * node.weight / (a0 * a0 * a0);
    const geometry::BasisRow& row = node.row;
    for (int a = 0; a < row.count; ++a)
      for (int b = a; b < row.count; ++b) {
        const double value = c * row.d2[a] * row.d2[b];
        entries.emplace_back(row.first + a, row.first + b, value);
        if (b != a) entries.emplace_back(row.first + b, row.first + a, value);
      }
  }
  const int n = spline.pointCount();
  stiffness_.resize(n, n);
  stiffness_.setFromTriplets(entries.begin(), entries.end());
  band_ = ScalarBand(stiffness_, spline.basis().degree());
  kq_.setZero(n, 3);
}

void ParametricBending::addForce(const SceneState& s, VecX& B) const {
  band_.subtractProduct(body().block(s.q), body().block(B));  // Q = −K_b q
}

double ParametricBending::potentialEnergy(const SceneState& s) const {
  const ConstPointsMap q = body().block(s.q);
  kq_.noalias() = stiffness_ * q;
  return 0.5 * q.cwiseProduct(kq_).sum();  // ½ Σ_α qᵀ K_b q
}

void ParametricBending::addJacobian(const SceneState&, double k_factor, double, JacobianAccumulator& out) const {
  if (k_factor == 0.0) return;
  // K = −K_b ⊗ I₃: the same constant band on every axis.
  const int base = body().offset();
  for (int i = 0; i < stiffness_.outerSize(); ++i)
    for (SparseMatrix::InnerIterator it(stiffness_, i); it; ++it)
      out.addIsotropic(base + i, base + static_cast<int>(it.col()), -k_factor * it.value());
}

}  // namespace filum::mechanics
