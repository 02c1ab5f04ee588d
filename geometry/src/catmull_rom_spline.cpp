#include "filum/geometry/catmull_rom_spline.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace filum::geometry {

CatmullRomSpline::CatmullRomSpline(int control_points) : n_(control_points) {
  if (n_ < kMinimumControlPoints)
    throw std::invalid_argument("a Catmull-Rom spline needs at least 4 control points, got " + std::to_string(n_));
}

void CatmullRomSpline::evaluate(double s, BasisRow& row) const {
  const int segments = n_ - 3;
  // s > 0 is false for NaN: a NaN abscissa (a diverging stage) evaluates at 0 instead of
  // indexing control point INT_MIN; the scene reports the non-finite state after the step.
  const double u = (s > 0.0 ? std::min(s, 1.0) : 0.0) * segments;
  evaluateSegment(std::min(static_cast<int>(std::floor(u)), segments - 1), u, row);
}

void CatmullRomSpline::evaluateFromLeft(double s, BasisRow& row) const {
  const int segments = n_ - 3;
  const double u = (s > 0.0 ? std::min(s, 1.0) : 0.0) * segments;
  // The segment that ends at u (j < u <= j + 1); the first one at u = 0.
  evaluateSegment(std::max(static_cast<int>(std::ceil(u)) - 1, 0), u, row);
}

void CatmullRomSpline::evaluateSegment(int j, double u, BasisRow& row) const {
  const int segments = n_ - 3;
  const double t = u - j, t2 = t * t, t3 = t2 * t;
  const double du = segments;  // du/ds
  row.first = j;
  row.count = 4;
  // ½ (−t³ + 2t² − t), ½ (3t³ − 5t² + 2), ½ (−3t³ + 4t² + t), ½ (t³ − t²)
  row.value[0] = 0.5 * (-t3 + 2.0 * t2 - t);
  row.value[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
  row.value[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
  row.value[3] = 0.5 * (t3 - t2);
  // d/dt, times du/ds
  row.d1[0] = 0.5 * (-3.0 * t2 + 4.0 * t - 1.0) * du;
  row.d1[1] = 0.5 * (9.0 * t2 - 10.0 * t) * du;
  row.d1[2] = 0.5 * (-9.0 * t2 + 8.0 * t + 1.0) * du;
  row.d1[3] = 0.5 * (3.0 * t2 - 2.0 * t) * du;
  // d²/dt², times (du/ds)²
  const double du2 = du * du;
  row.d2[0] = (-3.0 * t + 2.0) * du2;
  row.d2[1] = (9.0 * t - 5.0) * du2;
  row.d2[2] = (-9.0 * t + 4.0) * du2;
  row.d2[3] = (3.0 * t - 1.0) * du2;
  for (int k = 4; k < BasisRow::kMaxSupport; ++k) row.value[k] = row.d1[k] = row.d2[k] = 0.0;
}

std::vector<double> CatmullRomSpline::cuts() const { return {}; }  // C¹ everywhere: never cut

std::vector<double> CatmullRomSpline::breakpoints() const {
  const int segments = n_ - 3;
  std::vector<double> out(segments + 1);
  for (int j = 0; j <= segments; ++j) out[j] = static_cast<double>(j) / segments;
  out.back() = 1.0;
  return out;
}

double CatmullRomSpline::abscissaOfControlPoint(int i) const {
  if (i < 1 || i > n_ - 2)
    throw std::invalid_argument("CatmullRomSpline: the curve passes through control points 1.." +
                                std::to_string(n_ - 2) + " only, asked for " + std::to_string(i));
  return static_cast<double>(i - 1) / (n_ - 3);
}

Points withPhantomEndPoints(ConstPointsRef points) {
  const Eigen::Index m = points.rows();
  if (m < 2)
    throw std::invalid_argument("withPhantomEndPoints: need at least 2 points, got " + std::to_string(m));
  Points q(m + 2, 3);
  q.middleRows(1, m) = points;
  q.row(0) = 2.0 * points.row(0) - points.row(1);
  q.row(m + 1) = 2.0 * points.row(m - 1) - points.row(m - 2);
  return q;
}

}  // namespace filum::geometry
