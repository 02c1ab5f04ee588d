#include "filum/geometry/uniform_cubic_bspline.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace filum::geometry {

UniformCubicBSpline::UniformCubicBSpline(int control_points) : n_(control_points) {
  if (n_ < kMinimumControlPoints)
    throw std::invalid_argument("a uniform cubic B-spline needs at least 4 control points, got " +
                                std::to_string(n_));
}

void UniformCubicBSpline::evaluate(double s, BasisRow& row) const {
  const int segments = n_ - 3;
  // s > 0 is false for NaN: a NaN abscissa (a diverging stage) evaluates at 0 instead of
  // indexing control point INT_MIN; the scene reports the non-finite state after the step.
  const double u = (s > 0.0 ? std::min(s, 1.0) : 0.0) * segments;
  evaluateSegment(std::min(static_cast<int>(std::floor(u)), segments - 1), u, row);
}

void UniformCubicBSpline::evaluateFromLeft(double s, BasisRow& row) const {
  const int segments = n_ - 3;
  const double u = (s > 0.0 ? std::min(s, 1.0) : 0.0) * segments;
  // The segment that ends at u (j < u <= j + 1); the first one at u = 0.
  evaluateSegment(std::max(static_cast<int>(std::ceil(u)) - 1, 0), u, row);
}

void UniformCubicBSpline::evaluateSegment(int j, double u, BasisRow& row) const {
  const int segments = n_ - 3;
  const double t = u - j, t2 = t * t, t3 = t2 * t, mt = 1.0 - t;
  const double du = segments;  // du/ds
  row.first = j;
  row.count = 4;
  // Blending functions of the segment and their t-derivatives, scaled by (du/ds)^k.
  row.value[0] = mt * mt * mt / 6.0;
  row.value[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
  row.value[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
  row.value[3] = t3 / 6.0;
  row.d1[0] = -0.5 * mt * mt * du;
  row.d1[1] = (1.5 * t2 - 2.0 * t) * du;
  row.d1[2] = (-1.5 * t2 + t + 0.5) * du;
  row.d1[3] = 0.5 * t2 * du;
  row.d2[0] = mt * du * du;
  row.d2[1] = (3.0 * t - 2.0) * du * du;
  row.d2[2] = (-3.0 * t + 1.0) * du * du;
  row.d2[3] = t * du * du;
}

std::vector<double> UniformCubicBSpline::cuts() const { return {}; }  // C² everywhere: never cut

std::vector<double> UniformCubicBSpline::breakpoints() const {
  const int segments = n_ - 3;
  std::vector<double> out(segments + 1);
  for (int j = 0; j <= segments; ++j) out[j] = static_cast<double>(j) / segments;
  out.back() = 1.0;
  return out;
}

}  // namespace filum::geometry
