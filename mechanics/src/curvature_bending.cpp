#include "filum/mechanics/curvature_bending.hpp"

#include <cmath>

#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/mechanics/support_jacobian.hpp"

namespace filum::mechanics {

namespace {

/// Density e = β C r^(−5/2) at one node and its derivatives in x = P', y = P''.
struct BendingDensity {
  double energy;
  Vec3 gx, gy;               // ∂e/∂x, ∂e/∂y
  Eigen::Matrix3d hxx, hxy, hyy;  // ∂²e/∂x², ∂²e/∂x∂y (rows x, columns y), ∂²e/∂y²

  BendingDensity(double beta, const Vec3& x, const Vec3& y, bool hessian) {
    const double r = x.squaredNorm();
    if (r == 0.0) {  // degenerate parametrization: no curvature defined, no force
      energy = 0.0;
      gx.setZero();
      gy.setZero();
      hxx.setZero();
      hxy.setZero();
      hyy.setZero();
      return;
    }
    const double xy = x.dot(y), yy = y.squaredNorm();
    const double C = r * yy - xy * xy;  // |x × y|²
    const double f = 1.0 / (r * r * std::sqrt(r));  // r^(−5/2)
    const Vec3 Cx = 2.0 * (yy * x - xy * y);
    const Vec3 Cy = 2.0 * (r * y - xy * x);
    const Vec3 fx = (-5.0 * f / r) * x;
    energy = beta * C * f;
    gx = beta * (f * Cx + C * fx);
    gy = beta * f * Cy;
    if (!hessian) return;
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d Cxx = 2.0 * (yy * I - y * y.transpose());
    const Eigen::Matrix3d Cyy = 2.0 * (r * I - x * x.transpose());
    const Eigen::Matrix3d Cxy = 4.0 * x * y.transpose() - 2.0 * y * x.transpose() - 2.0 * xy * I;
    const Eigen::Matrix3d fxx = (-5.0 * f / r) * I + (35.0 * f / (r * r)) * x * x.transpose();
    hxx = beta * (f * Cxx + Cx * fx.transpose() + fx * Cx.transpose() + C * fxx);
    hxy = beta * (f * Cxy + fx * Cy.transpose());
    hyy = beta * f * Cyy;
  }
};

}  // namespace

std::unique_ptr<CurvatureBending> CurvatureBending::fromParams(const Params& p) {
  return std::make_unique<CurvatureBending>(p.positive("youngs_modulus"),
                                            p.has("quadrature_nodes") ? p.integer("quadrature_nodes", 1) : 0);
}

void CurvatureBending::init(const Scene&) {
  const DynamicSpline& spline = splineBody(*this);
  bending_stiffness_ = youngs_modulus_ * secondMomentOfArea(spline.radius());
  const int nodes = quadrature_nodes_ > 0 ? quadrature_nodes_ : defaultNodesPerPiece(spline.basis().degree());
  quadrature_ = CurveQuadrature(spline.basis(), nodes, spline.initialPositions(), std::nullopt);
}

void CurvatureBending::addForce(const SceneState& s, VecX& B) const {
  const ConstPointsMap q = body().block(s.q);
  PointsMap Q = body().block(B);
  for (const QuadratureNode& node : quadrature_.nodes()) {
    const BendingDensity e(0.5 * bending_stiffness_ * node.weight, geometry::curveTangent(node.row, q),
                           geometry::curveSecondDerivative(node.row, q), false);
    // Q_j = −(b'_j ∂e/∂x + b''_j ∂e/∂y)
    for (int j = 0; j < node.row.count; ++j)
      Q.row(node.row.first + j) -= (node.row.d1[j] * e.gx + node.row.d2[j] * e.gy).transpose();
  }
}

double CurvatureBending::potentialEnergy(const SceneState& s) const {
  const ConstPointsMap q = body().block(s.q);
  double energy = 0.0;
  for (const QuadratureNode& node : quadrature_.nodes()) {
    energy += BendingDensity(0.5 * bending_stiffness_ * node.weight, geometry::curveTangent(node.row, q),
                             geometry::curveSecondDerivative(node.row, q), false)
                  .energy;
  }
  return energy;
}

void CurvatureBending::addJacobian(const SceneState& s, double k_factor, double, JacobianAccumulator& out) const {
  if (k_factor == 0.0) return;
  const ConstPointsMap q = body().block(s.q);
  SupportJacobian jacobian(out, body().offset(), -k_factor);
  for (const QuadratureNode& node : quadrature_.nodes()) {
    const BendingDensity e(0.5 * bending_stiffness_ * node.weight, geometry::curveTangent(node.row, q),
                           geometry::curveSecondDerivative(node.row, q), true);
    jacobian.begin(node.row);
    jacobian.add(node.row.d1, node.row.d1, e.hxx);
    jacobian.add(node.row.d1, node.row.d2, e.hxy);
    jacobian.add(node.row.d2, node.row.d1, e.hxy.transpose());
    jacobian.add(node.row.d2, node.row.d2, e.hyy);
  }
}

}  // namespace filum::mechanics
