#include "filum/mechanics/green_lagrange_stretching.hpp"

#include <algorithm>

#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/mechanics/support_jacobian.hpp"

namespace filum::mechanics {

std::unique_ptr<GreenLagrangeStretching> GreenLagrangeStretching::fromParams(const Params& p) {
  const std::string jacobian = p.string("jacobian", "exact");
  if (jacobian != "exact" && jacobian != "definite") p.fail("jacobian", "\"exact\" or \"definite\"", "\"" + jacobian + "\"");
  return std::make_unique<GreenLagrangeStretching>(ElasticParameters::fromParams(p), jacobian == "definite");
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
  // Elastic: D = 0. K = −∇²E, so k_factor·K is the Hessian scaled by −k_factor. Per piece of the
  // spline (its nodes share one support), block (a, b) of the Hessian is
  //   Σ_g b'_a b'_b c_g (ε_g I + x_g x_gᵀ / a0²) = (Σ_g p_g ε_g c_g) I + Σ_g p_g (c_g / a0²) x_g x_gᵀ,
  // p_g = b'_a(s_g) b'_b(s_g): 6 distinct entries of a symmetric outer product and one isotropic
  // term per node and pair a >= b, instead of a full 3 × 3 product per node and pair. With the
  // definite Jacobian the isotropic term c ε is clamped at 0 (compression).
  if (k_factor == 0.0) return;
  const ConstPointsMap q = body().block(s.q);
  const auto& nodes = quadrature_.nodes();
  constexpr int kMax = geometry::BasisRow::kMaxSupport;
  constexpr int kPairs = kMax * (kMax + 1) / 2;
  // Column k of `sums`: pair k = (a, b <= a) of the piece; rows xx xy xz yy yz zz, isotropic, 0.
  Eigen::Matrix<double, 8, kPairs> sums;
  Eigen::Matrix<double, 8, 1> outer;
  Eigen::Matrix<double, 1, kPairs> products;
  const double scale = -k_factor;
  const int base = body().offset();
  std::size_t g = 0;
  while (g < nodes.size()) {
    const int first = nodes[g].row.first, count = nodes[g].row.count, pairs = count * (count + 1) / 2;
    sums.leftCols(pairs).setZero();
    for (; g < nodes.size() && nodes[g].row.first == first && nodes[g].row.count == count; ++g) {
      const QuadratureNode& node = nodes[g];
      const Vec3 x = geometry::curveTangent(node.row, q);
      const double a0sq = node.rest_speed * node.rest_speed;
      const double beta = c_[g] / a0sq;
      double isotropic = c_[g] * (x.squaredNorm() - a0sq) / (2.0 * a0sq);  // c ε
      if (definite_jacobian_) isotropic = std::max(isotropic, 0.0);
      outer << beta * x.x() * x.x(), beta * x.x() * x.y(), beta * x.x() * x.z(), beta * x.y() * x.y(),
          beta * x.y() * x.z(), beta * x.z() * x.z(), isotropic, 0.0;
      int k = 0;
      for (int a = 0; a < count; ++a)
        for (int b = 0; b <= a; ++b) products[k++] = node.row.d1[a] * node.row.d1[b];
      if (pairs == 10)  // the cubic B-spline: fixed sizes, unrolled
        sums.leftCols<10>().noalias() += outer * products.leftCols<10>();
      else
        sums.leftCols(pairs).noalias() += outer * products.leftCols(pairs);  // rank-one update
    }
    int k = 0;
    for (int a = 0; a < count; ++a)
      for (int b = 0; b <= a; ++b, ++k) {
        const auto m = sums.col(k);
        Eigen::Matrix3d block;
        block << m[0] + m[6], m[1], m[2], m[1], m[3] + m[6], m[4], m[2], m[4], m[5] + m[6];
        block *= scale;
        if (a == b)
          out.addBlock(base + first + a, base + first + a, block);
        else
          out.addBlockPair(base + first + a, base + first + b, block);
      }
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
