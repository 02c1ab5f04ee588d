#include "filum/mechanics/global_stretching.hpp"

#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/mechanics/support_jacobian.hpp"

namespace filum::mechanics {

std::unique_ptr<GlobalStretching> GlobalStretching::fromParams(const Params& p) {
  return std::make_unique<GlobalStretching>(ElasticParameters::fromParams(p));
}

void GlobalStretching::init(const Scene&) {
  const DynamicSpline& spline = splineBody(*this);
  const int nodes = parameters_.quadrature_nodes > 0 ? parameters_.quadrature_nodes
                                                     : defaultNodesPerPiece(spline.basis().degree());
  quadrature_ = CurveQuadrature(spline.basis(), nodes, spline.initialPositions(), parameters_.rest_length);
  // k = E A l0 / 4 (paper §3)
  k_ = parameters_.youngs_modulus * crossSectionArea(spline.radius()) * quadrature_.restLength() / 4.0;
  gradient_.setZero(spline.pointCount(), 3);
}

double GlobalStretching::lengthAndGradient(ConstPointsRef q) const {
  // l = Σ_g w_g |x_g|,  ∂l/∂q_j = Σ_g w_g b'_j u_g
  gradient_.setZero();
  double l = 0.0;
  for (const QuadratureNode& node : quadrature_.nodes()) {
    const Vec3 x = geometry::curveTangent(node.row, q);
    const double speed = x.norm();
    l += node.weight * speed;
    if (speed == 0.0) continue;  // direction undefined: no contribution to the gradient
    const Eigen::RowVector3d wu = (node.weight / speed) * x.transpose();
    for (int j = 0; j < node.row.count; ++j) gradient_.row(node.row.first + j) += node.row.d1[j] * wu;
  }
  return l;
}

double GlobalStretching::length(const SceneState& s) const {
  double l = 0.0;
  for (const QuadratureNode& node : quadrature_.nodes())
    l += node.weight * geometry::curveTangent(node.row, body().block(s.q)).norm();
  return l;
}

void GlobalStretching::addForce(const SceneState& s, VecX& B) const {
  const double l = lengthAndGradient(body().block(s.q));
  const double l0sq = quadrature_.restLength() * quadrature_.restLength();
  const double dE = 2.0 * k_ * (l * l / l0sq - 1.0) * l / l0sq;  // Ê'(l)
  body().block(B) -= dE * gradient_;                              // Q = −Ê'(l) ∇l
}

double GlobalStretching::potentialEnergy(const SceneState& s) const {
  const double l = length(s), l0 = quadrature_.restLength();
  const double r = l * l / (l0 * l0) - 1.0;
  return 0.5 * k_ * r * r;  // Ê = ½ k (l²/l0² − 1)²
}

void GlobalStretching::addJacobian(const SceneState& s, double k_factor, double /*d_factor*/,
                                    JacobianAccumulator& out) const {
  if (k_factor == 0.0) return;
  const ConstPointsMap q = body().block(s.q);
  const double l = lengthAndGradient(q);
  const double l0sq = quadrature_.restLength() * quadrature_.restLength();
  const double r = l * l / l0sq - 1.0;
  const double dE = 2.0 * k_ * r * l / l0sq;                              // Ê'(l)
  const double d2E = 2.0 * k_ * (r / l0sq + 2.0 * l * l / (l0sq * l0sq));  // Ê''(l)

  // Local part Ê'(l) ∇²l, ∇²l = Σ_g w_g b'_i b'_j (I − u uᵀ)/|x|, scaled by −k_factor.
  {
    SupportJacobian local(out, body().offset(), -k_factor);
    for (const QuadratureNode& node : quadrature_.nodes()) {
      const Vec3 x = geometry::curveTangent(node.row, q);
      const double speed = x.norm();
      if (speed == 0.0) continue;
      const Vec3 u = x / speed;
      const Eigen::Matrix3d H = (dE * node.weight / speed) * (Eigen::Matrix3d::Identity() - u * u.transpose());
      local.begin(node.row);
      local.addSymmetric(node.row.d1, H);
    }
  }
  // Rank-one part Ê''(l) ∇l ∇lᵀ: kept apart by the band step matrix (Sherman–Morrison).
  out.addRankOne(body().offset(), gradient_, -k_factor * d2E);
}

}  // namespace filum::mechanics
