#include "filum/geometry/rotation_vector.hpp"

#include <cmath>

namespace filum::geometry {

Eigen::Quaterniond rotationExp(const Vec3& w) {
  const double angle = w.norm();
  if (angle < 0.1) {
    // Small turns (a rod frame's per-step increment): cos(θ/2) and sin(θ/2)/θ by their Taylor
    // series in x = θ/2 to x⁸ (the first left out, x¹⁰/10!, is below 3e-20 at x = 0.05: round-off),
    // no sin/cos calls.
    const double x2 = 0.25 * angle * angle;
    const double c = 1.0 - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0 * (1.0 - x2 / 90.0))));
    const double s = 0.5 * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0))));
    const Vec3 axis = s * w;
    return Eigen::Quaterniond(c, axis.x(), axis.y(), axis.z());  // unit to round-off: c² + (sθ)² = 1 by the series
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
// c(θ) = 1/θ² − (1 + cos θ)/(2 θ sin θ) = Σ_{n>=1} |B_2n| θ^{2n−2} / (2n)!  (B: Bernoulli numbers,
// from the series of cot(θ/2)): below θ = 0.25 by that series to θ¹⁰ (the first term left out,
// |B_14| θ¹² / 14! ≈ 8e-19 there: round-off), which also avoids the closed form's cancellation
// (ε / θ² relative) and its sin and cos calls — a rod's nodes turn by a few degrees.
double secondOrderCoefficient(double angle) {
  if (angle < 0.25) {
    const double t2 = angle * angle;
    return 1.0 / 12.0 + t2 * (1.0 / 720.0 + t2 * (1.0 / 30240.0 + t2 * (1.0 / 1209600.0 + t2 * (1.0 / 47900160.0 +
                                                                                                 t2 * (691.0 / 2730.0 / 479001600.0)))));
  }
  return 1.0 / (angle * angle) - (1.0 + std::cos(angle)) / (2.0 * angle * std::sin(angle));
}
}  // namespace

Eigen::Matrix3d rightJacobianInverse(const Vec3& phi) {
  const Eigen::Matrix3d hat = skew(phi);
  return Eigen::Matrix3d::Identity() + 0.5 * hat + secondOrderCoefficient(phi.norm()) * hat * hat;
}

Eigen::Matrix3d leftJacobianInverse(const Vec3& phi) { return rightJacobianInverse(-phi); }

void jacobianInverseTransposeTimes(const Vec3& phi, const Vec3& m, Vec3& right, Vec3& left) {
  const Vec3 half = 0.5 * phi.cross(m), second = secondOrderCoefficient(phi.norm()) * phi.cross(phi.cross(m));
  right = m - half + second;
  left = m + half + second;
}

}  // namespace filum::geometry
