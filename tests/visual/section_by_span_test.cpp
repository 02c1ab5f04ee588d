// Skins of a rod whose section changes along it ("spans" with a radius of their own: a thick
// shaft and a thin tip): spheres on the rod take the radius at their abscissa, and the
// convolution surface wraps each part at its own radius. (The generalized cylinder's profile is
// checked in generalized_cylinder_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "filum/core/curve_body.hpp"
#include "filum/visual/convolution_surface_mesher.hpp"
#include "filum/visual/convolution_surface_model.hpp"
#include "filum/visual/sphere_model.hpp"
#include "filum/visual/visual_scene.hpp"
#include "visual/visual_test_support.hpp"

namespace filum::visual {
namespace {

using nlohmann::json;

constexpr double kShaft = 1e-3, kTip = 4e-4;

template <typename Model>
const Model& onlyModel(const VisualScene& visuals) {
  const Model* found = nullptr;
  for (const VisualModel* model : visuals.models())
    if (const auto* m = dynamic_cast<const Model*>(model)) found = m;
  if (!found) throw std::logic_error("no such visual model in the scene");
  return *found;
}

TEST(SectionBySpan, SpheresOnARodTakeItsRadiusAtTheirAbscissa) {
  // A 20-segment rod whose second half is a thin tip: a sphere on the shaft, one at the node of
  // the step (the larger side's), one on the tip.
  const json more = json::array({{{"type", "SphereModel"}, {"abscissas", {0.25, 0.5, 0.75}}}});
  auto scene = loadScene(test::rodWithThinTip(0.2, 21, kShaft, 0.5, kTip, more), "spans", test::visualFactory());
  VisualScene visuals(*scene);
  visuals.update(scene->state());
  const SphereModel& spheres = onlyModel<SphereModel>(visuals);
  ASSERT_EQ(spheres.radii().size(), 3);
  EXPECT_EQ(spheres.radii()[0], kShaft);
  EXPECT_EQ(spheres.radii()[1], kShaft);
  EXPECT_EQ(spheres.radii()[2], kTip);
  EXPECT_EQ(spheres.radius(), kShaft);
  // Each sphere's vertices lie at its own radius from its centre: a unit vertex scaled and moved
  // to the centre, so the distance is exact but for a few roundings of the centre's coordinates.
  const TriangleMesh& mesh = spheres.mesh();
  const Eigen::Index per_sphere = mesh.vertices.rows() / 3;
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    const Eigen::Index k = v / per_sphere;
    const double distance = (mesh.vertices.row(v) - spheres.centers().row(k)).norm();
    const double roundings = 4 * std::numeric_limits<double>::epsilon() * (spheres.centers().row(k).norm() + kShaft);
    EXPECT_NEAR(distance, spheres.radii()[k], roundings) << "vertex " << v;
  }
}

TEST(SectionBySpan, ARadiusGivenToTheSpheresHoldsAllAlong) {
  const json more = json::array({{{"type", "SphereModel"}, {"count", 5}, {"radius", 2e-3}}});
  auto scene = loadScene(test::rodWithThinTip(0.2, 21, kShaft, 0.5, kTip, more), "spans", test::visualFactory());
  VisualScene visuals(*scene);
  visuals.update(scene->state());
  const SphereModel& spheres = onlyModel<SphereModel>(visuals);
  EXPECT_EQ(spheres.radii().size(), 0);
  EXPECT_EQ(spheres.radius(), 2e-3);
}

TEST(SectionBySpan, TheConvolutionSurfaceWrapsShaftAndTipAtTheirOwnRadii) {
  // A straight rod 40 mm long, its second half a tip of 0.4 mm against the shaft's 1 mm; the
  // surface's kernel is the shaft's (s = 1/R = 1/mm), each chord weighted to its own radius.
  // (Facets of the tip's radius instead of the default half: the mesh is four times coarser, the
  // vertices as close to the surface.)
  const json more = json::array({{{"type", "ConvolutionSurfaceModel"}, {"facet_size", kTip}}});
  const json document = test::rodWithThinTip(0.04, 21, kShaft, 0.5, kTip, more);
  if (test::refusedWithoutCgal(document, "spans")) return;  // a build without CGAL refuses the skin
  auto scene = loadScene(document, "spans", test::visualFactory());
  VisualScene visuals(*scene);
  visuals.update(scene->state());
  const TriangleMesh& mesh = onlyModel<ConvolutionSurfaceModel>(visuals).mesh();
  const test::ManifoldReport report = test::checkClosedManifold(mesh);
  EXPECT_TRUE(report.closed && report.consistently_oriented) << report.first_problem;
  // Vertices 8 mm or more from the ends and from the step (x = 20 mm): the field there is an
  // infinite tube's of weight w_i but for the kernel beyond D = 8 mm = 8/s, |ΔF| <=
  // (2 w_i + w_j) / (3 s⁴ D³) (convolution_surface_test.cpp, AWeightedTubeTakesTheRadiusOfItsWeight),
  // which moves the radius by |ΔF| / (w_i |dF∞/dd|), twice that for the slope's change; the
  // mesher puts vertices on the surface to 1e-3 of its approximation bound (0.05 × 0.4 mm, the
  // thinnest section's default).
  const double s = 1.0 / kShaft;
  auto line = [s](double d) { return std::numbers::pi / (2.0 * s * std::pow(1.0 + s * s * d * d, 1.5)); };
  auto slope = [s](double d) { return 3.0 * std::numbers::pi * s * d / (2.0 * std::pow(1.0 + s * s * d * d, 2.5)); };
  const double iso = line(kShaft);  // a long tube of weight 1 has the kernel's radius
  const double w_shaft = 1.0, w_tip = iso / line(kTip);
  const double tail = 1.0 / (3.0 * std::pow(s, 4) * std::pow(8e-3, 3)), on_surface = 1e-3 * 0.05 * kTip + 1e-9;
  const double shaft_error = 2.0 * (2.0 * w_shaft + w_tip) * tail / (w_shaft * slope(kShaft)) + on_surface;
  const double tip_error = 2.0 * (2.0 * w_tip + w_shaft) * tail / (w_tip * slope(kTip)) + on_surface;
  int on_shaft = 0, on_tip = 0;
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    const Vec3 x = mesh.vertices.row(v).transpose();
    const double from_axis = std::hypot(x.y(), x.z());
    if (x.x() >= 8e-3 && x.x() <= 12e-3) {
      EXPECT_NEAR(from_axis, kShaft, shaft_error) << "vertex " << v << " at x = " << x.x();
      ++on_shaft;
    }
    if (x.x() >= 28e-3 && x.x() <= 32e-3) {
      EXPECT_NEAR(from_axis, kTip, tip_error) << "vertex " << v << " at x = " << x.x();
      ++on_tip;
    }
  }
  EXPECT_GT(on_shaft, 20);
  EXPECT_GT(on_tip, 20);
  EXPECT_LT(tip_error, 0.05 * kTip);  // far below the step of 0.6 mm one radius would miss by
}

}  // namespace
}  // namespace filum::visual
