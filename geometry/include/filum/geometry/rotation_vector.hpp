// Rotations as rotation vectors (the exponential coordinates of SO(3)): what a body with a
// rotation per segment (a rod) needs to move its frames and to differentiate energies of
// relative rotations (a Cosserat rod's bending and twist). With φ̂ the cross-product matrix of
// φ and θ = |φ|:
//   exp(φ) = the turn by θ about φ/θ  (as a unit quaternion),   log = its inverse (θ <= π),
//   right Jacobian inverse  J_r⁻¹(φ) = I + ½ φ̂ + c(θ) φ̂²,   left  J_l⁻¹(φ) = J_r⁻¹(−φ),
//   c(θ) = 1/θ² − (1 + cos θ) / (2 θ sin θ)   (→ 1/12 as θ → 0),
// so that log(exp(φ) exp(δ)) = φ + J_r⁻¹(φ) δ + O(δ²) and log(exp(δ) exp(φ)) = φ + J_l⁻¹(φ) δ + O(δ²)
// (Barfoot, State Estimation for Robotics, §7.1.3; Solà et al., A micro Lie theory, 2018).
#pragma once

#include <Eigen/Geometry>

#include "filum/core/types.hpp"

namespace filum::geometry {

/// The unit quaternion of the rotation vector w (a turn by |w| about w / |w|).
Eigen::Quaterniond rotationExp(const Vec3& w);
/// The rotation vector of a unit quaternion, of angle in [0, π].
Vec3 rotationLog(const Eigen::Quaterniond& q);
/// J_r⁻¹(φ) and J_l⁻¹(φ) (header).
Eigen::Matrix3d rightJacobianInverse(const Vec3& phi);
Eigen::Matrix3d leftJacobianInverse(const Vec3& phi);
/// J_r⁻¹(φ)ᵀ m and J_l⁻¹(φ)ᵀ m without forming the matrices (φ̂ᵀ = −φ̂):
///   J_r⁻ᵀ m = m − ½ φ × m + c(θ) φ × (φ × m),   J_l⁻ᵀ m = m + ½ φ × m + c(θ) φ × (φ × m)
/// (a torque from a moment m on the rotation vector φ; a rod's joints need both).
void jacobianInverseTransposeTimes(const Vec3& phi, const Vec3& m, Vec3& right, Vec3& left);
/// The cross-product matrix φ̂ (φ̂ x = φ × x).
Eigen::Matrix3d skew(const Vec3& phi);

/// A quaternion as the state stores it, (w, x, y, z) from wxyz[0..3] (Eigen's own order is x y z w).
inline Eigen::Quaterniond unpackQuaternion(const double* wxyz) {
  return Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
}
inline void packQuaternion(const Eigen::Quaterniond& r, double* wxyz) {
  wxyz[0] = r.w();
  wxyz[1] = r.x();
  wxyz[2] = r.y();
  wxyz[3] = r.z();
}

}  // namespace filum::geometry
