#include "filum/mechanics/green_lagrange_stretching.hpp"

#include <algorithm>
#include <cmath>

#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/mechanics/support_jacobian.hpp"

namespace filum::mechanics {

namespace {

/// A pair's Hessian block from its sums m = (xx, xy, xz, yy, yz, zz, isotropic):
/// Σ p c/a0² x xᵀ + (Σ p c ε) I.
void pairBlock(const double* m, Eigen::Matrix3d& block) {
  block << m[0] + m[6], m[1], m[2], m[1], m[3] + m[6], m[4], m[2], m[4], m[5] + m[6];
}

}  // namespace

std::unique_ptr<GreenLagrangeStretching> GreenLagrangeStretching::fromParams(const Params& p) {
  const std::string jacobian = p.string("jacobian", "exact");
  if (jacobian != "exact" && jacobian != "definite") p.fail("jacobian", "\"exact\" or \"definite\"", "\"" + jacobian + "\"");
  auto field = std::make_unique<GreenLagrangeStretching>(ElasticParameters::fromParams(p), jacobian == "definite");
  if (p.has({"break_force", "N"}) && p.has({"tensile_strength", "Pa"}))
    p.fail("tensile_strength", "either \"break_force\" (N) or \"tensile_strength\" (Pa), not both", "both");
  if (p.has({"break_force", "N"})) field->setBreakForce(p.positive({"break_force", "N"}));
  if (p.has({"tensile_strength", "Pa"})) field->setTensileStrength(p.positive({"tensile_strength", "Pa"}));
  return field;
}

bool GreenLagrangeStretching::tearsAt(const SceneState& s, double& abscissa, double& tension) const {
  if (!std::isfinite(break_force_)) return false;
  // N = E A ε |P'|/|P0'| at each node (the header); the largest, if above the break force.
  const double* q = body().block(s.q).data();
  double largest = -std::numeric_limits<double>::infinity();
  int at = -1;
  for (const QuadraturePiece& piece : quadrature_.pieces()) {
    const double* points = q + 3 * piece.first;
    for (int g = piece.begin; g < piece.end; ++g) {
      const Node& node = nodes_[g];
      Vec3 x = Vec3::Zero();
      for (int j = 0; j < piece.count; ++j) x += node.d1[j] * Vec3(points[3 * j], points[3 * j + 1], points[3 * j + 2]);
      const double speed_sq = x.squaredNorm();
      const double n = axial_stiffness_ * (speed_sq - node.a0sq) / (2.0 * node.a0sq) * std::sqrt(speed_sq / node.a0sq);
      if (n > largest) {
        largest = n;
        at = g;
      }
    }
  }
  if (at < 0 || !(largest > break_force_)) return false;
  abscissa = node_abscissas_[at];
  tension = largest;
  return true;
}

void GreenLagrangeStretching::init(const Scene&) {
  const DynamicSpline& spline = splineBody(*this);
  axial_stiffness_ = parameters_.youngs_modulus * crossSectionArea(spline.radius());
  const int k = parameters_.quadrature_nodes > 0 ? parameters_.quadrature_nodes
                                                 : defaultNodesPerPiece(spline.basis().degree());
  quadrature_ = CurveQuadrature(spline.basis(), k, spline.initialPositions(), parameters_.rest_length);
  if (std::isfinite(tensile_strength_)) break_force_ = tensile_strength_ * crossSectionArea(spline.radius());
  c_.clear();
  nodes_.clear();
  node_abscissas_.clear();
  for (const QuadratureNode& node : quadrature_.nodes()) {
    node_abscissas_.push_back(node.s);
    c_.push_back(axial_stiffness_ * node.weight / node.rest_speed);
    nodes_.push_back({node.row.d1, c_.back(), node.rest_speed * node.rest_speed});
  }
  hessian_.reset(quadrature_.pieces().size(), spline.pointCount());
  // Every piece with 4 points and 5 nodes (the uniform cubic B-spline's default): the packed
  // fixed-size form of addCubicPieceForces.
  cubic_pieces_.clear();
  const auto& pieces = quadrature_.pieces();
  if (std::all_of(pieces.begin(), pieces.end(),
                  [](const QuadraturePiece& piece) { return piece.count == 4 && piece.end - piece.begin == 5; })) {
    cubic_pieces_.resize(pieces.size());
    for (std::size_t p = 0; p < pieces.size(); ++p)
      for (int g = 0; g < 5; ++g) {
        const Node& node = nodes_[pieces[p].begin + g];
        for (int j = 0; j < 4; ++j) cubic_pieces_[p].d1(g, j) = node.d1[j];
        cubic_pieces_[p].c[g] = node.c;
        cubic_pieces_[p].a0sq[g] = node.a0sq;
        cubic_pieces_[p].inverse_2a0sq[g] = 1.0 / (2.0 * node.a0sq);
        for (int a = 0, k = 0; a < 4; ++a)
          for (int b = 0; b <= a; ++b, ++k) cubic_pieces_[p].pair_products(g, k) = node.d1[a] * node.d1[b];
      }
  }
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

void GreenLagrangeStretching::addCubicPieceForces(const double* q, double* Q) const {
  // The uniform cubic B-spline with 5 nodes per piece (the default): per piece, as fixed-size
  // products the compiler vectorizes,
  //   X = B' P (5 × 3: x_g = P'(s_g) in row g),  S = diag(c_g ε_g) X,  Q_piece −= B'ᵀ S,
  // with B' (5 × 4) the nodes' basis derivatives and P (4 × 3) the piece's control points.
  using Points4 = Eigen::Matrix<double, 4, 3, Eigen::RowMajor>;
  for (std::size_t p = 0; p < quadrature_.pieces().size(); ++p) {
    const QuadraturePiece& piece = quadrature_.pieces()[p];
    const CubicPiece& cubic = cubic_pieces_[p];
    const Eigen::Map<const Points4> points(q + 3 * piece.first);
    Eigen::Matrix<double, 5, 3> x = cubic.d1 * points;
    const Eigen::Matrix<double, 5, 1> scale =
        cubic.c.cwiseProduct(x.rowwise().squaredNorm() - cubic.a0sq).cwiseProduct(cubic.inverse_2a0sq);  // c ε
    x.array().colwise() *= scale.array();
    Eigen::Map<Points4>(Q + 3 * piece.first).noalias() -= cubic.d1.transpose() * x;
  }
}

void GreenLagrangeStretching::addForce(const SceneState& s, VecX& B) const {
  const double* q = body().block(s.q).data();
  double* Q = body().block(B).data();
  if (!cubic_pieces_.empty()) {
    addCubicPieceForces(q, Q);
    return;
  }
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
                 const QuadraturePiece& piece = quadrature_.pieces()[p];
                 if (!cubic_pieces_.empty())
                   cubicPieceHessian(piece, cubic_pieces_[p], points, blocks);
                 else if (piece.count == 4)  // the cubic B-spline: fixed sizes, unrolled
                   pieceHessian<4>(piece, points, blocks);
                 else
                   pieceHessian<0>(piece, points, blocks);
               });
}

template <int Count>
void GreenLagrangeStretching::pieceHessian(const QuadraturePiece& piece, const double* q,
                                           Eigen::Matrix3d* blocks) const {
  // Block (a, b) of the Hessian over one piece (its nodes share one support) is
  //   Σ_g b'_a b'_b c_g (ε_g I + x_g x_gᵀ / a0²) = (Σ_g p_g ε_g c_g) I + Σ_g p_g (c_g / a0²) x_g x_gᵀ,
  // p_g = b'_a(s_g) b'_b(s_g): 6 distinct entries of a symmetric outer product and one isotropic
  // term per node and pair a >= b, instead of a full 3 × 3 product per node and pair. With the
  // definite Jacobian the isotropic term c ε is clamped at 0 (compression).
  constexpr int kMax = geometry::BasisRow::kMaxSupport;
  constexpr int kPairs = Count > 0 ? Count * (Count + 1) / 2 : kMax * (kMax + 1) / 2;
  const int count = Count > 0 ? Count : piece.count, pairs = count * (count + 1) / 2;
  // sums[k]: pair k = (a, b <= a) of the piece; xx xy xz yy yz zz, isotropic.
  std::array<std::array<double, 7>, kPairs> sums{};
  const double* points = q + 3 * piece.first;
  for (int g = piece.begin; g < piece.end; ++g) {
    const Node& node = nodes_[g];
    double x[3] = {0.0, 0.0, 0.0};  // P'(s_g)
    for (int j = 0; j < count; ++j)
      for (int c = 0; c < 3; ++c) x[c] += node.d1[j] * points[3 * j + c];
    const double beta = node.c / node.a0sq;
    double isotropic = node.c * (x[0] * x[0] + x[1] * x[1] + x[2] * x[2] - node.a0sq) / (2.0 * node.a0sq);  // c ε
    if (definite_jacobian_) isotropic = std::max(isotropic, 0.0);
    const double outer[7] = {beta * x[0] * x[0], beta * x[0] * x[1], beta * x[0] * x[2], beta * x[1] * x[1],
                             beta * x[1] * x[2], beta * x[2] * x[2], isotropic};
    for (int a = 0, k = 0; a < count; ++a)
      for (int b = 0; b <= a; ++b, ++k) {
        const double p = node.d1[a] * node.d1[b];
        for (int r = 0; r < 7; ++r) sums[k][r] += p * outer[r];
      }
  }
  for (int k = 0; k < pairs; ++k) pairBlock(sums[k].data(), blocks[k]);
}

void GreenLagrangeStretching::cubicPieceHessian(const QuadraturePiece& piece, const CubicPiece& cubic, const double* q,
                                                Eigen::Matrix3d* blocks) const {
  // pieceHessian's sums as one fixed-size product: sums (7 × 10) = O (7 × 5) · Π (5 × 10), column g
  // of O the node's xx xy xz yy yz zz terms β x xᵀ and its isotropic term c ε, Π(g, k) the pair
  // k's basis product b'_a b'_b at node g (kept with the piece).
  using Points4 = Eigen::Matrix<double, 4, 3, Eigen::RowMajor>;
  const Eigen::Map<const Points4> points(q + 3 * piece.first);
  const Eigen::Matrix<double, 5, 3> x = cubic.d1 * points;
  const Eigen::Matrix<double, 5, 1> beta = cubic.c.cwiseQuotient(cubic.a0sq);
  Eigen::Matrix<double, 5, 1> isotropic =
      cubic.c.cwiseProduct(x.rowwise().squaredNorm() - cubic.a0sq).cwiseProduct(cubic.inverse_2a0sq);  // c ε
  if (definite_jacobian_) isotropic = isotropic.cwiseMax(0.0);
  Eigen::Matrix<double, 5, 7> outer;  // row g: O's column g
  outer.col(0) = beta.cwiseProduct(x.col(0).cwiseProduct(x.col(0)));
  outer.col(1) = beta.cwiseProduct(x.col(0).cwiseProduct(x.col(1)));
  outer.col(2) = beta.cwiseProduct(x.col(0).cwiseProduct(x.col(2)));
  outer.col(3) = beta.cwiseProduct(x.col(1).cwiseProduct(x.col(1)));
  outer.col(4) = beta.cwiseProduct(x.col(1).cwiseProduct(x.col(2)));
  outer.col(5) = beta.cwiseProduct(x.col(2).cwiseProduct(x.col(2)));
  outer.col(6) = isotropic;
  const Eigen::Matrix<double, 7, 10> sums = outer.transpose() * cubic.pair_products;
  for (int k = 0; k < 10; ++k) pairBlock(sums.col(k).data(), blocks[k]);
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
