// Spheres along a spline at equal curvilinear spacing, resampled as the thread stretches, and a
// mapping whose Jacobian is the basis values (forces go up through b_i(s_k)).
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "collision_scenes.hpp"
#include "support/finite_difference.hpp"
#include "filum/collision/sphere_collision_model.hpp"
#include "filum/geometry/arc_length.hpp"
#include "filum/geometry/spline_basis_factory.hpp"
#include "filum/geometry/uniform_cubic_bspline.hpp"

namespace filum::collision {
namespace {

Points wavyControlPoints(int n) {
  Points q(n, 3);
  for (int i = 0; i < n; ++i) q.row(i) << 0.01 * i, 0.01 * std::sin(0.9 * i), 0.005 * std::cos(1.3 * i);
  return q;
}

TEST(SphereSamplingMapping, SpheresAreEquallySpacedAlongTheCurveAndFollowItsStretching) {
  const geometry::UniformCubicBSpline basis(12);
  const Points q = wavyControlPoints(12);
  const double h = 1e-3;  // target spacing (m)
  SphereSamplingMapping mapping(basis, h);
  mapping.resample(q);
  const geometry::ArcLengthParameterization arc(basis, q);
  const double L = arc.totalLength();
  // K = ⌈L/h⌉ + 1 spheres, spacing L/(K − 1) <= h.
  EXPECT_EQ(mapping.outputCount(), static_cast<int>(std::ceil(L / h)) + 1);
  EXPECT_LE(mapping.spacing(), h);
  EXPECT_NEAR(mapping.length(), L, 1e-9 * L);  // 4-point Gauss on eighths of pieces vs adaptive quadrature
  // Equal curvilinear spacing: L(s_{k+1}) − L(s_k) = spacing to the quadrature tolerance.
  const auto& s = mapping.abscissas();
  for (int k = 0; k + 1 < mapping.outputCount(); ++k)
    EXPECT_NEAR(arc.lengthAt(s[k + 1]) - arc.lengthAt(s[k]), mapping.spacing(), 2e-6 * L);

  // The thread stretched by half: 50 % more spheres, still at most h apart.
  const int before = mapping.outputCount();
  mapping.resample(1.5 * q);
  EXPECT_NEAR(mapping.outputCount() - 1, 1.5 * (before - 1), 1.0);
  EXPECT_LE(mapping.spacing(), h);
}

TEST(SphereSamplingMapping, APolylinesVerticesAreCentresHoweverUnequalItsPieces) {
  // A rod's centre line: degree 1 through 11 vertices on a zigzag whose pieces differ in length
  // (2.2 to 4.1 mm, as a rod stretched unevenly). Its centres are placed piece by piece,
  // ⌈ℓ_p / h⌉ on each piece p, so every vertex is a centre, exactly at its breakpoint (i/10, where
  // the row is the vertex's point alone); inside a piece the centres are equally spaced (a
  // linear piece has a constant |P'|), at most h apart.
  geometry::SplineBasisSpec spec;
  spec.name = "nubs";
  spec.degree = 1;
  spec.control_points = 11;
  const auto basis = geometry::makeSplineBasis(spec);
  Points q(11, 3);
  double x = 0.0;
  for (int i = 0; i < 11; ++i) {
    q.row(i) << x, (i % 2) * 1e-3, 0.0;
    x += 2e-3 + 2e-3 * (i % 3) / 2.0;  // pieces along x of 2, 3 and 4 mm
  }
  const double h = 1e-3;
  SphereSamplingMapping mapping(*basis, h);
  mapping.resample(q);
  std::vector<int> vertex_centre{0};
  for (int i = 0; i < 10; ++i)
    vertex_centre.push_back(vertex_centre.back() + static_cast<int>(std::ceil((q.row(i + 1) - q.row(i)).norm() / h)));
  ASSERT_EQ(mapping.outputCount(), vertex_centre.back() + 1);
  EXPECT_LE(mapping.spacing(), h);
  const auto& s = mapping.abscissas();
  for (int i = 0; i <= 10; ++i) {
    EXPECT_EQ(s[vertex_centre[i]], i / 10.0) << "vertex " << i;
    const geometry::BasisRow& row = mapping.row(vertex_centre[i]);
    for (int j = 0; j < row.count; ++j)
      EXPECT_EQ(row.value[j], row.first + j == i ? 1.0 : 0.0) << "vertex " << i << ", point " << row.first + j;
  }
  Points centres(mapping.outputCount(), 3);
  mapping.apply(q, centres);
  for (int i = 0; i < 10; ++i) {
    const int m = vertex_centre[i + 1] - vertex_centre[i];
    const double chord = (q.row(i + 1) - q.row(i)).norm() / m;
    EXPECT_LE(chord, h);
    for (int k = vertex_centre[i]; k < vertex_centre[i + 1]; ++k)
      // Round-off: centres (1 − u) q_i + u q_{i+1} of coordinates below 3 cm, a few ulps each
      // (ε · 3e-2 m ≈ 7e-18 m), their differences and norms: 1e-15 m is a hundred times that.
      EXPECT_NEAR((centres.row(k + 1) - centres.row(k)).norm(), chord, 1e-15) << "piece " << i << ", centre " << k;
  }
}

TEST(SphereSamplingMapping, JacobianIsTheBasisValuesAndApplyJTItsTranspose) {
  const geometry::UniformCubicBSpline basis(9);
  const Points q = wavyControlPoints(9);
  SphereSamplingMapping mapping(basis, 5e-3);
  mapping.resample(q);
  const int K = mapping.outputCount();
  const SparseMatrix J = mapping.jacobian(q);
  // apply is linear: x = J q (flattened).
  Points x(K, 3);
  mapping.apply(q, x);
  Points q_copy = q;
  const VecX Jq = J * Eigen::Map<const VecX>(q_copy.data(), q_copy.size());
  EXPECT_LT((Jq - Eigen::Map<const VecX>(x.data(), x.size())).cwiseAbs().maxCoeff(), 1e-15);
  // applyJT accumulates Jᵀ f.
  Points f = Points::Random(K, 3);
  Points Q = Points::Ones(9, 3);
  mapping.applyJT(q, f, Q);
  const VecX expected = VecX::Ones(27) + J.transpose() * Eigen::Map<const VecX>(f.data(), f.size());
  EXPECT_LT((Eigen::Map<const VecX>(Q.data(), Q.size()) - expected).cwiseAbs().maxCoeff(), 1e-14);
  // The generic mapping test (applyJT = transpose of applyJ, applyJ = central differences of
  // apply, jacobian()·v = applyJ): the mapping is linear, so central differences only carry
  // round-off ε |x| / h ≈ 2e-16 · 0.1 m / 1e-6 = 2e-11 (tolerance relative to 1 + |J v| ≈ 10).
  test::expectMappingConsistent(mapping, q, 1e-6, 1e-10);
}

TEST(SphereCollisionModel, ScenesWithoutCollisionModelsSkipCollisionEntirely) {
  test::CollisionThread thread;
  thread.control_points = {{"from", {0, 0, 0}}, {"to", {0.1, 0, 0}}, {"count", 8}};
  thread.collision = false;
  auto scene = test::loadCollisionScene(test::collisionScene({thread}, {{"type", "ContactPipeline"}}));
  EXPECT_EQ(scene->collisionPipeline(), nullptr);
  EXPECT_TRUE(scene->step().ok);

  thread.collision = true;
  scene = test::loadCollisionScene(test::collisionScene({thread}, {{"type", "ContactPipeline"}}));
  ASSERT_NE(scene->collisionPipeline(), nullptr);
  EXPECT_TRUE(scene->step().ok);
  // 10 cm at spacing r = 1 mm: 101 spheres.
  EXPECT_EQ(test::pipelineOf(*scene).statistics().spheres, 101);
}

}  // namespace
}  // namespace filum::collision
