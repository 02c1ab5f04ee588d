// Rotation vectors (geometry/rotation_vector.hpp): exp and log are inverse, and the Jacobian
// inverses are the derivatives of log under right and left increments, at small, middle and
// large angles (up to 3 rad, near π where c(θ) grows).
// Tolerances: central differences with step 1e-6 rad have truncation |δ|² |∂³ log| ~ 1e-12 and
// round-off ε / 1e-6 ~ 2e-10: 1e-8 asserted. log∘exp to 8 ε relative (a few roundings).
#include <gtest/gtest.h>

#include <limits>

#include "filum/geometry/rotation_vector.hpp"

namespace filum::geometry {
namespace {

TEST(RotationVector, ExpAndLogAreInverse) {
  for (const Vec3& phi : {Vec3(0, 0, 0), Vec3(1e-10, -2e-10, 0), Vec3(0.3, -0.2, 0.1), Vec3(Vec3(1.0, 2.0, -0.5).normalized() * 3.0)})
    EXPECT_LE((rotationLog(rotationExp(phi)) - phi).norm(), 8 * std::numeric_limits<double>::epsilon() * phi.norm())
        << phi.transpose();
}

TEST(RotationVector, JacobianInversesDifferentiateTheLogarithm) {
  const double h = 1e-6;
  for (const Vec3& phi : {Vec3(1e-6, 0, 0), Vec3(0.3, -0.2, 0.1), Vec3(Vec3(1.0, 2.0, -0.5).normalized() * 3.0)}) {
    Eigen::Matrix3d right, left;
    for (int k = 0; k < 3; ++k) {
      const Vec3 d = h * Vec3::Unit(k);
      right.col(k) = (rotationLog(rotationExp(phi) * rotationExp(d)) - rotationLog(rotationExp(phi) * rotationExp(-d))) / (2 * h);
      left.col(k) = (rotationLog(rotationExp(d) * rotationExp(phi)) - rotationLog(rotationExp(-d) * rotationExp(phi))) / (2 * h);
    }
    EXPECT_LE((right - rightJacobianInverse(phi)).cwiseAbs().maxCoeff(), 1e-8) << phi.transpose();
    EXPECT_LE((left - leftJacobianInverse(phi)).cwiseAbs().maxCoeff(), 1e-8) << phi.transpose();
  }
}

}  // namespace
}  // namespace filum::geometry

namespace filum::geometry {
namespace {

TEST(RotationVector, SeriesBranchesAgreeWithTheClosedForms) {
  // exp below 0.1 rad and J⁻¹ below 0.25 rad use Taylor series (no sin/cos): against the closed
  // forms in long double (cancellation-free at these angles: ε_long / θ² <= 1e-17), to 4 ε.
  for (const double angle : {1e-6, 1e-3, 0.05, 0.0999, 0.1001, 0.2, 0.2499, 0.2501}) {
    const Vec3 axis = Vec3(0.3, -0.5, 0.8).normalized(), phi = angle * axis;
    const Eigen::Quaterniond exact(Eigen::AngleAxisd(angle, axis));
    EXPECT_LE((rotationExp(phi).coeffs() - exact.coeffs()).cwiseAbs().maxCoeff(), 4e-16) << angle;
    const long double t = angle;
    const long double c = 1.0L / (t * t) - (1.0L + std::cos(t)) / (2.0L * t * std::sin(t));
    const Eigen::Matrix3d hat = skew(phi);
    const Eigen::Matrix3d reference = Eigen::Matrix3d::Identity() + 0.5 * hat + static_cast<double>(c) * hat * hat;
    EXPECT_LE((rightJacobianInverse(phi) - reference).cwiseAbs().maxCoeff(), 4e-16)
        << angle;
  }
}

}  // namespace
}  // namespace filum::geometry

namespace filum::geometry {
namespace {

TEST(RotationVector, TransposeProductsMatchTheMatrices) {
  // J⁻ᵀ m by cross products against the matrices: the same sums in another order, 8 ε relative.
  for (const double angle : {1e-3, 0.1, 0.3, 2.0}) {
    const Vec3 phi = angle * Vec3(0.3, -0.5, 0.8).normalized(), m(1.5, -0.2, 0.7);
    Vec3 right, left;
    jacobianInverseTransposeTimes(phi, m, right, left);
    EXPECT_LE((right - rightJacobianInverse(phi).transpose() * m).norm(), 8 * std::numeric_limits<double>::epsilon() * m.norm() * (1 + angle * angle));
    EXPECT_LE((left - leftJacobianInverse(phi).transpose() * m).norm(), 8 * std::numeric_limits<double>::epsilon() * m.norm() * (1 + angle * angle));
  }
}

}  // namespace
}  // namespace filum::geometry
