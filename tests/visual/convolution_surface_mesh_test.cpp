// Implicit surfaces meshed for display: CGAL's surface mesher on a convolution surface
// gives a closed, outward-oriented 2-manifold lying on the surface within the approximation
// bound; the ConvolutionSurfaceModel wraps a spline. Without CGAL (FILUM_WITH_CGAL=OFF) the
// component is refused with an error naming the option.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "filum/core/scene_error.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/visual/convolution_surface_mesher.hpp"
#include "filum/visual/visual_scene.hpp"
#include "visual/visual_test_support.hpp"

namespace filum::visual {
namespace {

using nlohmann::json;

TEST(ConvolutionSurfaceMesher, StraightTubeIsAClosedManifoldOnTheSurface) {
  if (!convolutionSurfaceMeshingAvailable()) GTEST_SKIP() << "built without CGAL (FILUM_WITH_CGAL=OFF)";
  const double R = 2e-3;
  geometry::ConvolutionSurface surface(R);
  surface.addSegment(Vec3(0, 0, 0), Vec3(0.02, 0, 0));
  SurfaceMeshingCriteria criteria;
  criteria.facet_size = 0.5 * R;
  criteria.approximation = 0.02 * R;
  const TriangleMesh mesh = meshConvolutionSurface(surface, Vec3(0.01, 0, 0), 0.02, criteria);
  const test::ManifoldReport r = test::checkClosedManifold(mesh);
  EXPECT_TRUE(r.closed && r.consistently_oriented && r.vertex_manifold && r.no_degenerate) << r.first_problem;
  EXPECT_EQ(r.euler_characteristic, 2);
  EXPECT_GT(test::signedVolume(mesh), 0.0);
  // Vertices are surface points (f = 0 to the bisection accuracy); normals are unit, outward.
  double worst = 0.0;
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    const Vec3 x = mesh.vertices.row(v).transpose();
    worst = std::max(worst, std::abs(surface.implicitValue(x)) / surface.fieldGradient(x).norm());  // ≈ distance
    EXPECT_NEAR(mesh.normals.row(v).norm(), 1.0, 1e-12);
    if (x.x() > 0.005 && x.x() < 0.015) {  // the middle: a tube of radius R about the x axis
      EXPECT_NEAR(std::hypot(x.y(), x.z()), R, 0.05 * R);
      EXPECT_GT(mesh.normals.row(v).dot(Vec3(0, x.y(), x.z()).normalized().transpose()), 0.99);
    }
  }
  EXPECT_LE(worst, 1e-3 * criteria.approximation + 1e-9);
}

TEST(ConvolutionSurfaceMesher, TheSameSurfaceGivesTheSameMeshWhateverWasMeshedBefore) {
  // Determinism: CGAL draws the mesher's first surface points from its default random generator;
  // a surface meshed again after another gives the same mesh, bit for bit.
  const double R = 2e-3;
  geometry::ConvolutionSurface tube(R), other(R);
  tube.addSegment(Vec3(0, 0, 0), Vec3(0.02, 0, 0));
  other.addSegment(Vec3(0, 0, 0), Vec3(0, 0.01, 0));
  SurfaceMeshingCriteria criteria;
  criteria.facet_size = 0.5 * R;
  criteria.approximation = 0.05 * R;
  if (!convolutionSurfaceMeshingAvailable()) {  // a build without CGAL refuses, naming the option
    try {
      meshConvolutionSurface(tube, Vec3(0.01, 0, 0), 0.02, criteria);
      FAIL() << "meshed without CGAL";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("FILUM_WITH_CGAL"), std::string::npos) << e.what();
    }
    return;
  }
  const TriangleMesh first = meshConvolutionSurface(tube, Vec3(0.01, 0, 0), 0.02, criteria);
  meshConvolutionSurface(other, Vec3(0, 0.005, 0), 0.02, criteria);
  const TriangleMesh again = meshConvolutionSurface(tube, Vec3(0.01, 0, 0), 0.02, criteria);
  ASSERT_EQ(first.vertices.rows(), again.vertices.rows());
  EXPECT_TRUE(first.vertices == again.vertices);
  EXPECT_TRUE(first.triangles == again.triangles);
}

TEST(ConvolutionSurfaceModel, WrapsASplineOrIsRefusedWithTheOption) {
  const json more = json::array({{{"type", "ConvolutionSurfaceModel"}, {"radius", 3e-3}, {"facet_size", 2e-3}}});
  const json document = test::splineScene(test::helix(12), more, 1e-3);
  if (test::refusedWithoutCgal(document, "scene.json")) return;
  auto scene = loadScene(document, "scene.json", test::visualFactory());
  VisualScene visuals(*scene);
  ASSERT_EQ(visuals.models().size(), 1u);  // the surface draws the body: no default skin
  visuals.update(scene->state());
  const TriangleMesh& mesh = visuals.models().front()->mesh();
  const test::ManifoldReport r = test::checkClosedManifold(mesh);
  EXPECT_TRUE(r.closed && r.consistently_oriented) << r.first_problem;
  EXPECT_GT(mesh.triangleCount(), 200);
  // Every vertex is within a few radii of the axis.
  const auto& spline = *scene->bodies().front()->curve();
  for (int v = 0; v < mesh.vertexCount(); v += 7) {
    double nearest = 1e9;
    for (int k = 0; k <= 400; ++k)
      nearest = std::min(nearest, (geometry::curvePoint(spline.basis(), spline.block(scene->state().q), k / 400.0) -
                                   mesh.vertices.row(v).transpose()).norm());
    EXPECT_LT(nearest, 2.0 * 3e-3);
  }
}

}  // namespace
}  // namespace filum::visual
