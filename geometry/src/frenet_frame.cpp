#include "filum/geometry/frenet_frame.hpp"

#include "filum/geometry/spline_curve.hpp"

namespace filum::geometry {

std::optional<CurveFrame> frenetFrame(const CurveBasis& basis, ConstPointsRef q, double s,
                                      double relative_threshold) {
  const CurveDerivatives c = curveDerivatives(basis, q, s);
  const double speed = c.first.norm();
  const Vec3 cross = c.first.cross(c.second);
  const double cross_norm = cross.norm();
  if (!(speed > 0.0) || !(cross_norm > relative_threshold * speed * c.second.norm())) return std::nullopt;
  CurveFrame frame;
  frame.origin = c.point;
  frame.tangent = c.first / speed;           // T = P'/|P'|
  frame.binormal = cross / cross_norm;       // B = P' × P'' / |P' × P''|
  frame.normal = frame.binormal.cross(frame.tangent);  // N = B × T
  return frame;
}

double curveCurvature(const CurveBasis& basis, ConstPointsRef q, double s) {
  const CurveDerivatives c = curveDerivatives(basis, q, s);
  const double speed = c.first.norm();
  if (!(speed > 0.0)) return 0.0;
  return c.first.cross(c.second).norm() / (speed * speed * speed);  // κ = |P' × P''| / |P'|³
}

}  // namespace filum::geometry
