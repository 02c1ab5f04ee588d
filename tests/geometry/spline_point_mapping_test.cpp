// The mapping contract (docs/architecture.md, "The three-sided model"): applyJT is the transpose
// of applyJ, applyJ matches finite differences of apply, jacobian() matches applyJ — for the
// spline point mapping.
#include <gtest/gtest.h>

#include "filum/geometry/uniform_cubic_bspline.hpp"
#include "filum/geometry/spline_point_mapping.hpp"
#include "support/finite_difference.hpp"

namespace filum::geometry {
namespace {

TEST(SplinePointMapping, PassesTheGenericMappingTest) {
  // The map is linear, so central differences have no truncation error: only round-off
  // ε |x| / h ≈ 2e-16 · 1 / 1e-4 = 2e-12 remains; 1e-10 bounds it with margin. The transpose
  // identity is exact up to summation round-off (~1e-15), inside 1e-12.
  const geometry::UniformCubicBSpline basis(30);
  const SplinePointMapping mapping(basis, {0.0, 0.013, 0.25, 0.5, 0.77, 0.999, 1.0});
  const Points q = test::randomPoints(30, 0.1, 3);
  test::expectMappingConsistent(mapping, q, 1e-4, 1e-10, 11);

  // applyJT alone, tighter: ⟨J v, f⟩ = ⟨v, Jᵀ f⟩ to 1e-12 relative.
  const Points v = test::randomPoints(30, 1.0, 5), f = test::randomPoints(7, 1.0, 6);
  Points jv(7, 3), jtf = Points::Zero(30, 3);
  mapping.applyJ(q, v, jv);
  mapping.applyJT(q, f, jtf);
  EXPECT_NEAR(jv.cwiseProduct(f).sum(), v.cwiseProduct(jtf).sum(), 1e-12 * v.norm() * f.norm());
}

TEST(SplinePointMapping, ApplyJTAccumulates) {
  const geometry::UniformCubicBSpline basis(10);
  const SplinePointMapping mapping(basis, uniformAbscissas(5));
  const Points q = test::randomPoints(10, 1.0, 1), f = test::randomPoints(5, 1.0, 2);
  Points once = Points::Zero(10, 3), twice = Points::Zero(10, 3);
  mapping.applyJT(q, f, once);
  mapping.applyJT(q, f, twice);
  mapping.applyJT(q, f, twice);
  EXPECT_LE((twice - 2.0 * once).norm(), 1e-15 * once.norm());
}

TEST(SplinePointMapping, MapsPointsOntoTheCurve) {
  // Basis rows sum to one: a curve whose control points all sit at X maps every point to X.
  const geometry::UniformCubicBSpline basis(8);
  const SplinePointMapping mapping(basis, uniformAbscissas(20));
  Points q(8, 3);
  q.rowwise() = Eigen::RowVector3d(0.1, -2.0, 3.0);
  Points x(20, 3);
  mapping.apply(q, x);
  for (int k = 0; k < 20; ++k) EXPECT_LE((x.row(k) - q.row(0)).norm(), 1e-15);
}

}  // namespace
}  // namespace filum::geometry
