#include "filum/mechanics/curvature_bending.hpp"

#include <array>
#include <cmath>

#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum::mechanics {

namespace {

/// Density e = β C r^(−5/2) at one node and its gradient in x = P', y = P'' (header):
///   ∂e/∂x = β f (2|y|² x − 2(x·y) y − 5 C/r x),   ∂e/∂y = β f (2 r y − 2 (x·y) x),   f = r^(−5/2).
struct BendingDensity {
  double energy;
  Vec3 gx, gy;  // ∂e/∂x, ∂e/∂y

  BendingDensity(double beta, const Vec3& x, const Vec3& y) {
    const double r = x.squaredNorm();
    if (r == 0.0) {  // degenerate parametrization: no curvature defined, no force
      energy = 0.0;
      gx.setZero();
      gy.setZero();
      return;
    }
    const double xy = x.dot(y), yy = y.squaredNorm();
    const double C = r * yy - xy * xy;  // |x × y|²
    const double bf = beta / (r * r * std::sqrt(r));  // β r^(−5/2)
    energy = bf * C;
    gx = bf * ((2.0 * yy - 5.0 * C / r) * x - 2.0 * xy * y);
    gy = bf * (2.0 * r * y - 2.0 * xy * x);
  }
};

/// The density's Hessian at one node as 21 numbers (what CurvatureBending::pieceHessian sums):
/// e_xx (6 entries of the symmetric block: 00 10 20 11 21 22), e_xy (9, column-major; rows x,
/// columns y), e_yy (6). From the header's derivatives,
/// collected on I, x xᵀ, x yᵀ, y xᵀ and y yᵀ (no 3 × 3 products):
///   e_xx = β f [(2|y|² − 5C/r) I + (35 C/r² − 20 |y|²/r) x xᵀ + 10 (x·y)/r (x yᵀ + y xᵀ) − 2 y yᵀ],
///   e_xy = β f [−2 (x·y) I + 10 (x·y)/r x xᵀ − 6 x yᵀ − 2 y xᵀ],
///   e_yy = β f [2 r I − 2 x xᵀ].
void densityHessian(double beta, const Vec3& x, const Vec3& y, std::array<double, 21>& h) {
  const double r = x.squaredNorm();
  if (r == 0.0) {
    h.fill(0.0);
    return;
  }
  const double xy = x.dot(y), yy = y.squaredNorm();
  const double C = r * yy - xy * xy;
  const double bf = beta / (r * r * std::sqrt(r));
  const double i_xx = bf * (2.0 * yy - 5.0 * C / r), c_xx = bf * (35.0 * C / (r * r) - 20.0 * yy / r);
  const double c_sym = bf * 10.0 * xy / r, c_yy = -2.0 * bf;
  const double i_xy = -2.0 * bf * xy, c_xy = -6.0 * bf, c_yx = -2.0 * bf;  // c_xx of e_xy is c_sym
  const double i_yy = 2.0 * bf * r;
  constexpr int kLower[6][2] = {{0, 0}, {1, 0}, {2, 0}, {1, 1}, {2, 1}, {2, 2}};
  for (int k = 0; k < 6; ++k) {
    const int i = kLower[k][0], j = kLower[k][1];
    const double delta = i == j ? 1.0 : 0.0;
    h[k] = i_xx * delta + c_xx * x[i] * x[j] + c_sym * (x[i] * y[j] + y[i] * x[j]) + c_yy * y[i] * y[j];
    h[15 + k] = i_yy * delta + c_yy * x[i] * x[j];
  }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      h[6 + i + 3 * j] = (i == j ? i_xy : 0.0) + c_sym * x[i] * x[j] + c_xy * x[i] * y[j] + c_yx * y[i] * x[j];
    }
}

}  // namespace

std::unique_ptr<CurvatureBending> CurvatureBending::fromParams(const Params& p) {
  return std::make_unique<CurvatureBending>(p.positive({"youngs_modulus", "Pa"}),
                                            p.has("quadrature_nodes") ? p.integer("quadrature_nodes", 1) : 0);
}

void CurvatureBending::init(const Scene&) {
  const DynamicSpline& spline = splineBody(*this);
  bending_stiffness_ = youngs_modulus_ * secondMomentOfArea(spline.radius());
  const int nodes = quadrature_nodes_ > 0 ? quadrature_nodes_ : defaultNodesPerPiece(spline.basis().degree());
  quadrature_ = CurveQuadrature(spline.basis(), nodes, spline.initialPositions(), std::nullopt);
  hessian_.reset(quadrature_.pieces().size(), spline.pointCount());
}

void CurvatureBending::addForce(const SceneState& s, VecX& B) const {
  const ConstPointsMap q = body().block(s.q);
  PointsMap Q = body().block(B);
  for (const QuadratureNode& node : quadrature_.nodes()) {
    const BendingDensity e(0.5 * bending_stiffness_ * node.weight, geometry::curveTangent(node.row, q),
                           geometry::curveSecondDerivative(node.row, q));
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
                             geometry::curveSecondDerivative(node.row, q))
                  .energy;
  }
  return energy;
}

void CurvatureBending::addJacobian(const SceneState& s, double k_factor, double, JacobianAccumulator& out) const {
  // K = −∇²E, so k_factor·K is the Hessian scaled by −k_factor. The Hessian's blocks are kept for
  // the positions they were computed at: RayleighDamping's lagged K and the step matrix both ask
  // at a step's first state, and the second request replays them (the density's second
  // derivatives are most of an implicit step's cost for a suture).
  if (k_factor == 0.0) return;
  const auto q = s.q.segment(3 * Eigen::Index(body().offset()), 3 * Eigen::Index(body().pointCount()));
  const int points = body().pointCount();
  hessian_.add(quadrature_.pieces(), q, k_factor, body().offset(), out,
               [this, points](std::size_t p, const double* coordinates, Eigen::Matrix3d* blocks) {
                 const ConstPointsMap positions(coordinates, points, 3);
                 const QuadraturePiece& piece = quadrature_.pieces()[p];
                 if (piece.count == 4)  // the cubic B-spline: fixed sizes, unrolled
                   pieceHessian<4>(piece, positions, blocks);
                 else
                   pieceHessian<0>(piece, positions, blocks);
               });
}

template <int Count>
void CurvatureBending::pieceHessian(const QuadraturePiece& piece, const ConstPointsMap& q, Eigen::Matrix3d* blocks) const {
  // By the chain rule through x = P' = Σ b'_j q_j and y = P'' = Σ b''_j q_j, block (a, b) of the
  // Hessian is
  //   Σ_g [b'_a b'_b e_xx + b'_a b''_b e_xy + b''_a b'_b e_xyᵀ + b''_a b''_b e_yy]_g,
  // symmetric as a whole (block (b, a) = block (a, b)ᵀ). The piece's nodes share one support: the
  // four sums are accumulated as rank-one updates over the pairs a >= b — the node's 21 Hessian
  // numbers times the pairs' basis products — and turned into 3 × 3 blocks once per pair.
  constexpr int kMax = geometry::BasisRow::kMaxSupport;
  constexpr int kPairs = Count > 0 ? Count * (Count + 1) / 2 : kMax * (kMax + 1) / 2;
  const int count = Count > 0 ? Count : piece.count, pairs = count * (count + 1) / 2;
  std::array<std::array<double, 30>, kPairs> sums{};  // per pair k: the four sums' 30 rows
  std::array<double, 21> h;  // e_xx, e_xy, e_yy at the node (densityHessian)
  std::array<std::array<double, kPairs>, 4> products;  // b'_a b'_b, b'_a b''_b, b''_a b'_b, b''_a b''_b
  const auto& nodes = quadrature_.nodes();
  for (int g = piece.begin; g < piece.end; ++g) {
    const geometry::BasisRow& row = nodes[g].row;
    densityHessian(0.5 * bending_stiffness_ * nodes[g].weight, geometry::curveTangent(row, q),
                   geometry::curveSecondDerivative(row, q), h);
    int k = 0;
    for (int a = 0; a < count; ++a)
      for (int b = 0; b <= a; ++b, ++k) {
        products[0][k] = row.d1[a] * row.d1[b];
        products[1][k] = row.d1[a] * row.d2[b];
        products[2][k] = row.d2[a] * row.d1[b];
        products[3][k] = row.d2[a] * row.d2[b];
      }
    for (k = 0; k < pairs; ++k) {
      double* column = sums[k].data();
      for (int r = 0; r < 6; ++r) column[r] += h[r] * products[0][k];
      for (int r = 6; r < 15; ++r) column[r] += h[r] * products[1][k];       // e_xy, b'_a b''_b
      for (int r = 6; r < 15; ++r) column[r + 9] += h[r] * products[2][k];   // e_xy, b''_a b'_b (transposed below)
      for (int r = 15; r < 21; ++r) column[r + 9] += h[r] * products[3][k];  // e_yy
    }
  }
  for (int k = 0; k < pairs; ++k) {
    const double* m = sums[k].data();
    Eigen::Matrix3d& block = blocks[k];
    block << m[0] + m[24], m[1] + m[25], m[2] + m[26],  //
        m[1] + m[25], m[3] + m[27], m[4] + m[28],      //
        m[2] + m[26], m[4] + m[28], m[5] + m[29];
    block += Eigen::Map<const Eigen::Matrix3d>(m + 6) + Eigen::Map<const Eigen::Matrix3d>(m + 15).transpose();
  }
}

}  // namespace filum::mechanics
