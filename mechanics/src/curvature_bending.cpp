#include "filum/mechanics/curvature_bending.hpp"

#include <cmath>

#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

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
  // K = −∇²E, so k_factor·K is the Hessian scaled by −k_factor. By the chain rule through
  // x = P' = Σ b'_j q_j and y = P'' = Σ b''_j q_j, block (a, b) of the Hessian is
  //   Σ_g [b'_a b'_b e_xx + b'_a b''_b e_xy + b''_a b'_b e_xyᵀ + b''_a b''_b e_yy]_g,
  // symmetric as a whole (block (b, a) = block (a, b)ᵀ). Per piece of the spline (its nodes share
  // one support) the four sums are accumulated as rank-one updates over the pairs a >= b — the
  // node's Hessian entries times the pairs' basis products — and emitted once per pair.
  if (k_factor == 0.0) return;
  const ConstPointsMap q = body().block(s.q);
  const auto& nodes = quadrature_.nodes();
  constexpr int kMax = geometry::BasisRow::kMaxSupport;
  constexpr int kPairs = kMax * (kMax + 1) / 2;
  // Rows: e_xx (6 entries of the symmetric block), e_xy for b'_a b''_b (9, column-major), e_xy
  // for b''_a b'_b (9, transposed when emitted), e_yy (6).
  Eigen::Matrix<double, 30, kPairs> sums;
  Eigen::Matrix<double, 6, 1> xx, yy;
  Eigen::Matrix<double, 9, 1> xy;
  Eigen::Matrix<double, 4, kPairs> products;  // rows: b'b', b'b'', b''b', b''b''
  const double scale = -k_factor;
  const int base = body().offset();
  const auto symmetric = [](const Eigen::Matrix3d& m, Eigen::Matrix<double, 6, 1>& v) {
    v << m(0, 0), m(1, 0), m(2, 0), m(1, 1), m(2, 1), m(2, 2);
  };
  std::size_t g = 0;
  while (g < nodes.size()) {
    const int first = nodes[g].row.first, count = nodes[g].row.count, pairs = count * (count + 1) / 2;
    sums.leftCols(pairs).setZero();
    for (; g < nodes.size() && nodes[g].row.first == first && nodes[g].row.count == count; ++g) {
      const geometry::BasisRow& row = nodes[g].row;
      const BendingDensity e(0.5 * bending_stiffness_ * nodes[g].weight, geometry::curveTangent(row, q),
                             geometry::curveSecondDerivative(row, q), true);
      symmetric(e.hxx, xx);
      symmetric(e.hyy, yy);
      xy = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(e.hxy.data());
      int k = 0;
      for (int a = 0; a < count; ++a)
        for (int b = 0; b <= a; ++b, ++k)
          products.col(k) << row.d1[a] * row.d1[b], row.d1[a] * row.d2[b], row.d2[a] * row.d1[b], row.d2[a] * row.d2[b];
      sums.topRows<6>().leftCols(pairs).noalias() += xx * products.row(0).head(pairs);
      sums.middleRows<9>(6).leftCols(pairs).noalias() += xy * products.row(1).head(pairs);
      sums.middleRows<9>(15).leftCols(pairs).noalias() += xy * products.row(2).head(pairs);
      sums.bottomRows<6>().leftCols(pairs).noalias() += yy * products.row(3).head(pairs);
    }
    int k = 0;
    for (int a = 0; a < count; ++a)
      for (int b = 0; b <= a; ++b, ++k) {
        const auto m = sums.col(k);
        Eigen::Matrix3d block;
        block << m[0] + m[24], m[1] + m[25], m[2] + m[26],  //
            m[1] + m[25], m[3] + m[27], m[4] + m[28],      //
            m[2] + m[26], m[4] + m[28], m[5] + m[29];
        block += Eigen::Map<const Eigen::Matrix3d>(m.data() + 6) + Eigen::Map<const Eigen::Matrix3d>(m.data() + 15).transpose();
        block *= scale;
        if (a == b)
          out.addBlock(base + first + a, base + first + a, block);
        else
          out.addBlockPair(base + first + a, base + first + b, block);
      }
  }
}

}  // namespace filum::mechanics
