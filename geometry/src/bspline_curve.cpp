#include "filum/geometry/bspline_curve.hpp"

#include <stdexcept>
#include <string>

#include "filum/geometry/catmull_rom_spline.hpp"
#include "filum/geometry/knot_vector.hpp"
#include "filum/geometry/uniform_cubic_bspline.hpp"

namespace filum::geometry {

void validateBSplineCurve(const BSplineCurve& curve, const char* what) {
  validateKnotVector(curve.degree, curve.controlPointCount(), curve.knots, what);
}

namespace {

BSplineCurve catmullRomInKnotForm(ConstPointsRef q) {
  const int n = static_cast<int>(q.rows()), segments = n - 3;
  BSplineCurve curve;
  curve.degree = 3;
  // Clamped, interior knots j = 1..N−1 doubled: 4 + 2(N − 1) + 4 = 2N + 6 = (2N + 2) + 3 + 1.
  curve.knots.assign(4, 0.0);
  for (int j = 1; j < segments; ++j) curve.knots.insert(curve.knots.end(), 2, static_cast<double>(j));
  curve.knots.insert(curve.knots.end(), 4, static_cast<double>(segments));
  curve.control_points.resize(2 * segments + 2, 3);
  curve.control_points.row(0) = q.row(1);
  for (int j = 0; j < segments; ++j) {
    // Hermite tangents m = (q_{j+2} − q_j)/2 in t; Bézier inner points at ±m/3.
    curve.control_points.row(1 + 2 * j) = q.row(j + 1) + (q.row(j + 2) - q.row(j)) / 6.0;
    curve.control_points.row(2 + 2 * j) = q.row(j + 2) - (q.row(j + 3) - q.row(j + 1)) / 6.0;
  }
  curve.control_points.row(2 * segments + 1) = q.row(n - 2);
  return curve;
}

}  // namespace

BSplineCurve toBSplineCurve(const CurveBasis& basis, ConstPointsRef q) {
  if (q.rows() != basis.controlPointCount())
    throw std::invalid_argument("toBSplineCurve: the " + basis.name() + " basis has " +
                                std::to_string(basis.controlPointCount()) + " control points but " +
                                std::to_string(q.rows()) + " were given");
  if (const auto* nubs = dynamic_cast<const NonUniformBSpline*>(&basis))
    return BSplineCurve{nubs->degree(), nubs->knots(), Points(q)};
  if (dynamic_cast<const UniformCubicBSpline*>(&basis))
    return BSplineCurve{3, uniformKnots(3, basis.controlPointCount()), Points(q)};
  if (dynamic_cast<const CatmullRomSpline*>(&basis)) return catmullRomInKnotForm(q);
  throw std::invalid_argument("toBSplineCurve: no knot form known for the basis '" + basis.name() + "'");
}

}  // namespace filum::geometry
