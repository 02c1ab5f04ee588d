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
