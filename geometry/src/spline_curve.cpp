#include "filum/geometry/spline_curve.hpp"

#include <stdexcept>
#include <string>

namespace filum::geometry {

Vec3 curvePoint(const CurveBasis& basis, ConstPointsRef q, double s) {
  BasisRow row;
  basis.evaluate(s, row);
  return curvePoint(row, q);
}

CurveDerivatives curveDerivatives(const CurveBasis& basis, ConstPointsRef q, double s) {
  BasisRow row;
  basis.evaluate(s, row);
  return curveDerivatives(row, q);
}

Points sampleCurve(const CurveBasis& basis, ConstPointsRef q, int count) {
  if (count < 2) throw std::invalid_argument("sampleCurve: count must be >= 2, got " + std::to_string(count));
  Points out(count, 3);
  BasisRow row;
  for (int k = 0; k < count; ++k) {
    basis.evaluate(static_cast<double>(k) / (count - 1), row);
    out.row(k) = curvePoint(row, q).transpose();
  }
  return out;
}

}  // namespace filum::geometry
