// Evaluation of a spline curve P(s) = Σ b_i(s) q_i and its derivatives
// P'(s) = Σ b'_i(s) q_i, P''(s) = Σ b''_i(s) q_i (paper eq. 1) from a basis row and the control
// points (n × 3); works for every CurveBasis (uniform cubic B-spline, Catmull-Rom, NUBS).
#pragma once

#include <Eigen/Core>

#include "filum/core/types.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::geometry {

/// Σ_j row.value[j] q_{first+j}
inline Vec3 curvePoint(const BasisRow& row, ConstPointsRef q) {
  Vec3 p = Vec3::Zero();
  for (int j = 0; j < row.count; ++j) p += row.value[j] * q.row(row.first + j).transpose();
  return p;
}
/// P'(s) = Σ_j b'_j q_j
inline Vec3 curveTangent(const BasisRow& row, ConstPointsRef q) {
  Vec3 p = Vec3::Zero();
  for (int j = 0; j < row.count; ++j) p += row.d1[j] * q.row(row.first + j).transpose();
  return p;
}
/// P''(s) = Σ_j b''_j q_j
inline Vec3 curveSecondDerivative(const BasisRow& row, ConstPointsRef q) {
  Vec3 p = Vec3::Zero();
  for (int j = 0; j < row.count; ++j) p += row.d2[j] * q.row(row.first + j).transpose();
  return p;
}

/// P(s) for one abscissa (evaluates the basis).
Vec3 curvePoint(const CurveBasis& basis, ConstPointsRef q, double s);

/// P(s), P'(s) = dP/ds and P''(s) = d²P/ds² at one abscissa (units of q, q per unit s, ...).
struct CurveDerivatives {
  Vec3 point;   // P(s)
  Vec3 first;   // P'(s)
  Vec3 second;  // P''(s)
};
inline CurveDerivatives curveDerivatives(const BasisRow& row, ConstPointsRef q) {
  CurveDerivatives out{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  for (int j = 0; j < row.count; ++j) {
    const Vec3 qj = q.row(row.first + j).transpose();
    out.point += row.value[j] * qj;
    out.first += row.d1[j] * qj;
    out.second += row.d2[j] * qj;
  }
  return out;
}
/// P, P', P'' at s ∈ [0, 1] (evaluates the basis; q has basis.controlPointCount() rows).
CurveDerivatives curveDerivatives(const CurveBasis& basis, ConstPointsRef q, double s);

/// Points at `count` abscissas equally spaced in s (count >= 2), one per row.
Points sampleCurve(const CurveBasis& basis, ConstPointsRef q, int count);

}  // namespace filum::geometry
