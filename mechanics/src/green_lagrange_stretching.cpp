#include "filum/mechanics/green_lagrange_stretching.hpp"

#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/mechanics/support_jacobian.hpp"

namespace filum::mechanics {

std::unique_ptr<GreenLagrangeStretching> GreenLagrangeStretching::fromParams(const Params& p) {
  return std::make_unique<GreenLagrangeStretching>(ElasticParameters::fromParams(p));
}

void GreenLagrangeStretching::init(const Scene&) {
  const DynamicSpline& spline = splineBody(*this);
  axial_stiffness_ = parameters_.youngs_modulus * crossSectionArea(spline.radius());
  const int k = parameters_.quadrature_nodes > 0 ? parameters_.quadrature_nodes
                                                 : defaultNodesPerPiece(spline.basis().degree());
  quadrature_ = CurveQuadrature(spline.basis(), k, spline.initialPositions(), parameters_.rest_length);
  c_.clear();
  for (const QuadratureNode& node : quadrature_.nodes()) c_.push_back(axial_stiffness_ * node.weight / node.rest_speed);
}

void GreenLagrangeStretching::addForce(const SceneState& s, VecX& B) const {
  const ConstPointsMap q = body().block(s.q);
  PointsMap Q = body().block(B);
  const auto& nodes = quadrature_.nodes();
  for (std::size_t g = 0; g < nodes.size(); ++g) {
    const QuadratureNode& node = nodes[g];
    const Vec3 x = geometry::curveTangent(node.row, q);
    const double a0sq = node.rest_speed * node.rest_speed;
    const double strain = (x.squaredNorm() - a0sq) / (2.0 * a0sq);  // ε
    const Eigen::RowVector3d dEdx = (c_[g] * strain) * x.transpose();  // c ε x
    for (int j = 0; j < node.row.count; ++j) Q.row(node.row.first + j) -= node.row.d1[j] * dEdx;
  }
}

double GreenLagrangeStretching::potentialEnergy(const SceneState& s) const {
  const ConstPointsMap q = body().block(s.q);
  const auto& nodes = quadrature_.nodes();
  double e = 0.0;
  for (std::size_t g = 0; g < nodes.size(); ++g) {
    const QuadratureNode& node = nodes[g];
    const double a0sq = node.rest_speed * node.rest_speed;
    const double strain = (geometry::curveTangent(node.row, q).squaredNorm() - a0sq) / (2.0 * a0sq);
    e += 0.5 * c_[g] * a0sq * strain * strain;  // ½ E A w a0 ε²
  }
  return e;
}

void GreenLagrangeStretching::addJacobian(const SceneState& s, double k_factor, double /*d_factor*/,
                                          JacobianAccumulator& out) const {
  // Elastic: D = 0. K = −∇²E, so k_factor·K is the Hessian scaled by −k_factor.
  if (k_factor == 0.0) return;
  const ConstPointsMap q = body().block(s.q);
  const auto& nodes = quadrature_.nodes();
  SupportJacobian jacobian(out, body().offset(), -k_factor);
  for (std::size_t g = 0; g < nodes.size(); ++g) {
    const QuadratureNode& node = nodes[g];
    const Vec3 x = geometry::curveTangent(node.row, q);
    const double a0sq = node.rest_speed * node.rest_speed;
    const double strain = (x.squaredNorm() - a0sq) / (2.0 * a0sq);
    const Eigen::Matrix3d H = c_[g] * (strain * Eigen::Matrix3d::Identity() + x * x.transpose() / a0sq);
    jacobian.begin(node.row);
    jacobian.addSymmetric(node.row.d1, H);
  }
}

void GreenLagrangeStretching::addStiffnessDerivative(const SceneState& s, const VecX& w, double factor,
                                                     JacobianAccumulator& out) const {
  if (factor == 0.0) return;
  const ConstPointsMap q = body().block(s.q);
  const ConstPointsMap wp = body().block(w);
  const auto& nodes = quadrature_.nodes();
  SupportJacobian derivative(out, body().offset(), -factor);  // ∂(K w)/∂q = −Σ b'b' ∂(H ω)/∂x
  for (std::size_t g = 0; g < nodes.size(); ++g) {
    const QuadratureNode& node = nodes[g];
    const Vec3 x = geometry::curveTangent(node.row, q);
    const Vec3 omega = geometry::curveTangent(node.row, wp);  // Σ b'_j w_j
    const double scale = c_[g] / (node.rest_speed * node.rest_speed);
    const Eigen::Matrix3d T =
        scale * (omega * x.transpose() + x.dot(omega) * Eigen::Matrix3d::Identity() + x * omega.transpose());
    derivative.begin(node.row);
    derivative.addSymmetric(node.row.d1, T);
  }
}

}  // namespace filum::mechanics
