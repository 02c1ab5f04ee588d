#include "filum/geometry/rotation_minimizing_frames.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "filum/geometry/spline_curve.hpp"

namespace filum::geometry {

Vec3 anyPerpendicular(const Vec3& t) {
  // Cross with the axis least aligned with t: |t × e| >= sqrt(2/3).
  Eigen::Index axis = 0;
  t.cwiseAbs().minCoeff(&axis);
  return t.cross(Vec3::Unit(axis)).normalized();
}

namespace {

/// r projected onto the plane ⊥ t (unit) and normalised; any perpendicular if r ∥ t.
Vec3 perpendicularUnit(const Vec3& r, const Vec3& t) {
  const Vec3 p = r - r.dot(t) * t;
  const double norm = p.norm();
  if (!(norm > 1e-12 * std::max(1.0, r.norm()))) return anyPerpendicular(t);
  return p / norm;
}

}  // namespace

std::vector<CurveFrame> rotationMinimizingFrames(ConstPointsRef points, ConstPointsRef unit_tangents,
                                                 const Vec3& initial_normal) {
  const Eigen::Index m = points.rows();
  if (m < 1 || unit_tangents.rows() != m)
    throw std::invalid_argument("rotationMinimizingFrames: need as many tangents as points (>= 1), got " +
                                std::to_string(m) + " points and " + std::to_string(unit_tangents.rows()) +
                                " tangents");
  for (Eigen::Index i = 0; i < m; ++i)
    if (!(std::abs(unit_tangents.row(i).norm() - 1.0) <= 1e-8))
      throw std::invalid_argument("rotationMinimizingFrames: tangent " + std::to_string(i) + " is not a unit vector");
  std::vector<CurveFrame> frames(static_cast<std::size_t>(m));
  Vec3 t = unit_tangents.row(0).transpose();
  Vec3 r = perpendicularUnit(initial_normal, t);
  frames[0] = CurveFrame{points.row(0).transpose(), t, r, t.cross(r)};
  for (Eigen::Index i = 0; i + 1 < m; ++i) {
    const Vec3 x0 = points.row(i).transpose(), x1 = points.row(i + 1).transpose();
    const Vec3 t1 = unit_tangents.row(i + 1).transpose();
    // R1: reflection in the bisecting plane of x_i, x_{i+1}.
    const Vec3 v1 = x1 - x0;
    const double c1 = v1.squaredNorm();
    Vec3 rL = r, tL = t;
    if (c1 > 0.0) {
      rL = r - (2.0 / c1) * v1.dot(r) * v1;
      tL = t - (2.0 / c1) * v1.dot(t) * v1;
    }
    // R2: reflection that maps t_i^L onto t_{i+1}.
    const Vec3 v2 = t1 - tL;
    const double c2 = v2.squaredNorm();
    Vec3 r1 = rL;
    if (c2 > 0.0) r1 = rL - (2.0 / c2) * v2.dot(rL) * v2;
    t = t1;
    r = perpendicularUnit(r1, t);
    frames[i + 1] = CurveFrame{x1, t, r, t.cross(r)};
  }
  return frames;
}

std::vector<CurveFrame> rotationMinimizingFrames(const CurveBasis& basis, ConstPointsRef q,
                                                 const std::vector<double>& abscissas, const Vec3& initial_normal) {
  if (q.rows() != basis.controlPointCount())
    throw std::invalid_argument("rotationMinimizingFrames: the basis has " +
                                std::to_string(basis.controlPointCount()) + " control points but q has " +
                                std::to_string(q.rows()) + " rows");
  const int m = static_cast<int>(abscissas.size());
  if (m < 1) throw std::invalid_argument("rotationMinimizingFrames: need at least one abscissa");
  Points x(m, 3), t = Points::Zero(m, 3);
  BasisRow row;
  int first_moving = -1;  // first abscissa where P' != 0
  for (int k = 0; k < m; ++k) {
    if (k > 0 && !(abscissas[k] >= abscissas[k - 1]))
      throw std::invalid_argument("rotationMinimizingFrames: abscissas must be non-decreasing (index " +
                                  std::to_string(k) + ")");
    basis.evaluate(abscissas[k], row);
    const CurveDerivatives c = curveDerivatives(row, q);
    x.row(k) = c.point.transpose();
    const double speed = c.first.norm();
    if (speed > 0.0) {
      t.row(k) = (c.first / speed).transpose();
      if (first_moving < 0) first_moving = k;
    } else if (k > 0) {
      t.row(k) = t.row(k - 1);  // P' = 0: keep the previous tangent
    }
  }
  // Before the first moving abscissa: its tangent (or any direction if the curve never moves).
  const Eigen::RowVector3d start = first_moving >= 0 ? Eigen::RowVector3d(t.row(first_moving)) : Eigen::RowVector3d(1, 0, 0);
  for (int k = 0; k < (first_moving >= 0 ? first_moving : m); ++k) t.row(k) = start;
  return rotationMinimizingFrames(x, t, initial_normal);
}

}  // namespace filum::geometry
