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
  nodes_.clear();
  for (const QuadratureNode& node : quadrature_.nodes()) {
    c_.push_back(axial_stiffness_ * node.weight / node.rest_speed);
    nodes_.push_back({node.row.d1, c_.back(), node.rest_speed * node.rest_speed});
  }
  hessian_.reset(quadrature_.pieces().size(), spline.pointCount());
}

template <int Count>
void GreenLagrangeStretching::addPieceForce(const QuadraturePiece& piece, const double* q, double* Q) const {
  // The piece's control points and forces stay in registers over its nodes.
  const int count = Count > 0 ? Count : piece.count;
  std::array<double, 3 * geometry::BasisRow::kMaxSupport> force{};
  const double* points = q + 3 * piece.first;
  for (int g = piece.begin; g < piece.end; ++g) {
    const Node& node = nodes_[g];
    double x[3] = {0.0, 0.0, 0.0};  // x = P'(s_g) = Σ_j b'_j q_j
    for (int j = 0; j < count; ++j)
      for (int k = 0; k < 3; ++k) x[k] += node.d1[j] * points[3 * j + k];
    const double strain = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2] - node.a0sq) / (2.0 * node.a0sq);  // ε
    const double scale = node.c * strain;  // ∂E_g/∂x = c ε x
    for (int j = 0; j < count; ++j)
      for (int k = 0; k < 3; ++k) force[3 * j + k] -= node.d1[j] * scale * x[k];  // Q_j −= b'_j c ε x
  }
  double* target = Q + 3 * piece.first;
  for (int i = 0; i < 3 * count; ++i) target[i] += force[i];
}

void GreenLagrangeStretching::addForce(const SceneState& s, VecX& B) const {
  const double* q = body().block(s.q).data();
  double* Q = body().block(B).data();
  for (const QuadraturePiece& piece : quadrature_.pieces()) {
    if (piece.count == 4)  // the cubic B-spline: the support size known at compile time
      addPieceForce<4>(piece, q, Q);
    else
      addPieceForce<0>(piece, q, Q);
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
  // Elastic: D = 0. K = −∇²E, so k_factor·K is the Hessian scaled by −k_factor; the Hessian is
  // kept for the positions it was computed at (SupportHessianCache).
  if (k_factor == 0.0) return;
  const auto q = s.q.segment(3 * Eigen::Index(body().offset()), 3 * Eigen::Index(body().pointCount()));
  hessian_.add(quadrature_.pieces(), q, k_factor, body().offset(), out,
               [this](std::size_t p, const double* points, Eigen::Matrix3d* blocks) {
                 pieceHessian(quadrature_.pieces()[p], points, blocks);
               });
}

void GreenLagrangeStretching::pieceHessian(const QuadraturePiece& piece, const double* q,
                                           Eigen::Matrix3d* blocks) const {
  // Block (a, b) of the Hessian over one piece (its nodes share one support) is
  //   Σ_g b'_a b'_b c_g (ε_g I + x_g x_gᵀ / a0²) = (Σ_g p_g ε_g c_g) I + Σ_g p_g (c_g / a0²) x_g x_gᵀ,
  // p_g = b'_a(s_g) b'_b(s_g): 6 distinct entries of a symmetric outer product and one isotropic
  // term per node and pair a >= b, instead of a full 3 × 3 product per node and pair. With the
  // definite Jacobian the isotropic term c ε is clamped at 0 (compression).
  constexpr int kMax = geometry::BasisRow::kMaxSupport;
  constexpr int kPairs = kMax * (kMax + 1) / 2;
  // Column k of `sums`: pair k = (a, b <= a) of the piece; rows xx xy xz yy yz zz, isotropic, 0.
  Eigen::Matrix<double, 8, kPairs> sums;
  Eigen::Matrix<double, 8, 1> outer;
  Eigen::Matrix<double, 1, kPairs> products;
  const int count = piece.count, pairs = count * (count + 1) / 2;
  const double* points = q + 3 * piece.first;
  sums.leftCols(pairs).setZero();
  for (int g = piece.begin; g < piece.end; ++g) {
    const Node& node = nodes_[g];
    Vec3 x = Vec3::Zero();  // P'(s_g)
    for (int j = 0; j < count; ++j) x += node.d1[j] * Vec3(points[3 * j], points[3 * j + 1], points[3 * j + 2]);
    const double beta = node.c / node.a0sq;
    double isotropic = node.c * (x.squaredNorm() - node.a0sq) / (2.0 * node.a0sq);  // c ε
    if (definite_jacobian_) isotropic = std::max(isotropic, 0.0);
    outer << beta * x.x() * x.x(), beta * x.x() * x.y(), beta * x.x() * x.z(), beta * x.y() * x.y(),
        beta * x.y() * x.z(), beta * x.z() * x.z(), isotropic, 0.0;
    int k = 0;
    for (int a = 0; a < count; ++a)
      for (int b = 0; b <= a; ++b) products[k++] = node.d1[a] * node.d1[b];
    if (pairs == 10)  // the cubic B-spline: fixed sizes, unrolled
      sums.leftCols<10>().noalias() += outer * products.leftCols<10>();
    else
      sums.leftCols(pairs).noalias() += outer * products.leftCols(pairs);  // rank-one update
  }
  for (int k = 0; k < pairs; ++k) {
    const auto m = sums.col(k);
    blocks[k] << m[0] + m[6], m[1], m[2], m[1], m[3] + m[6], m[4], m[2], m[4], m[5] + m[6];
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
