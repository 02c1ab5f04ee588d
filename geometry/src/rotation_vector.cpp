#include "filum/geometry/rotation_vector.hpp"

#include <cmath>

namespace filum::geometry {

Eigen::Quaterniond rotationExp(const Vec3& w) {
  const double angle = w.norm();
  if (angle < 1e-8) {  // sin(θ/2)/θ = ½ − θ²/48: the series to round-off below 1e-8
    const Vec3 axis = (0.5 - angle * angle / 48.0) * w;
    return Eigen::Quaterniond(1.0 - angle * angle / 8.0, axis.x(), axis.y(), axis.z()).normalized();
  }
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle));
}

Vec3 rotationLog(const Eigen::Quaterniond& q_in) {
  // q = (cos θ/2, sin θ/2 n) with w >= 0 (θ in [0, π]): θ = 2 atan2(|v|, w), robust near 0 and π.
  const Eigen::Quaterniond q = q_in.w() < 0.0 ? Eigen::Quaterniond(-q_in.coeffs()) : q_in;
  const Vec3 v = q.vec();
  const double s = v.norm();
  if (s < 1e-8) return (2.0 / q.w()) * v;  // θ/ sin(θ/2) → 2/cos(θ/2) as θ → 0, to round-off
  return (2.0 * std::atan2(s, q.w()) / s) * v;
}

Eigen::Matrix3d skew(const Vec3& p) {
  Eigen::Matrix3d m;
  m << 0.0, -p.z(), p.y(), p.z(), 0.0, -p.x(), -p.y(), p.x(), 0.0;
  return m;
}

namespace {
// c(θ) = 1/θ² − (1 + cos θ)/(2 θ sin θ), by its series 1/12 + θ²/720 below 1e-4 (cancellation).
double secondOrderCoefficient(double angle) {
  if (angle < 1e-4) return 1.0 / 12.0 + angle * angle / 720.0;
  return 1.0 / (angle * angle) - (1.0 + std::cos(angle)) / (2.0 * angle * std::sin(angle));
}
}  // namespace

Eigen::Matrix3d rightJacobianInverse(const Vec3& phi) {
  const Eigen::Matrix3d hat = skew(phi);
  return Eigen::Matrix3d::Identity() + 0.5 * hat + secondOrderCoefficient(phi.norm()) * hat * hat;
}

Eigen::Matrix3d leftJacobianInverse(const Vec3& phi) { return rightJacobianInverse(-phi); }

}  // namespace filum::geometry
