// Skinning: the generalized cylinder around a spline axis is a closed, consistently
// oriented 2-manifold, its vertices lie at the requested radius from the axis (to 1e-9 m), its
// frames do not twist on a planar curve, its normals are unit and outward, and the mapping that
// carries the control points down to the axis passes the generic mapping test.
#include <gtest/gtest.h>

#include "filum/core/curve_body.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "filum/core/scene_error.hpp"
#include "filum/geometry/arc_length.hpp"
#include "filum/geometry/uniform_cubic_bspline.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/visual/generalized_cylinder_model.hpp"
#include "filum/visual/visual_scene.hpp"
#include "support/finite_difference.hpp"
#include "visual/visual_test_support.hpp"

namespace filum::visual {
namespace {

using nlohmann::json;

/// Loads a one-spline scene and returns it with its visual scene updated at t = 0.
struct Loaded {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<VisualScene> visuals;
};
Loaded load(const json& document) {
  Loaded l;
  l.scene = loadScene(document, "test", test::visualFactory());
  l.visuals = std::make_unique<VisualScene>(*l.scene);
  l.visuals->update(l.scene->state());
  return l;
}

const GeneralizedCylinderModel& skinOf(const Loaded& l) {
  for (const VisualModel* m : l.visuals->models())
    if (const auto* skin = dynamic_cast<const GeneralizedCylinderModel*>(m)) return *skin;
  throw std::logic_error("no skin");
}

void expectClosedOrientedManifold(const TriangleMesh& mesh, double weld = 0.0) {
  const test::ManifoldReport r = test::checkClosedManifold(mesh, weld);
  EXPECT_TRUE(r.no_degenerate) << r.first_problem;
  EXPECT_TRUE(r.closed) << r.first_problem;
  EXPECT_TRUE(r.consistently_oriented) << r.first_problem;
  EXPECT_TRUE(r.vertex_manifold) << r.first_problem;
  EXPECT_EQ(r.euler_characteristic, 2) << "a closed tube is a topological sphere";
  EXPECT_GT(test::signedVolume(mesh), 0.0) << "triangles must face outward";
}

TEST(GeneralizedCylinder, RoundCapsMakeAClosedConsistentlyOrientedManifold) {
  for (const json& points : {test::planarWave(), test::helix()}) {
    const Loaded l = load(test::splineScene(points, json::array({{{"type", "GeneralizedCylinder"}, {"sides", 12}}})));
    expectClosedOrientedManifold(skinOf(l).mesh());
  }
}

TEST(GeneralizedCylinder, FlatCapsAreClosedOnceTheirRimIsWelded) {
  const Loaded l = load(test::splineScene(test::helix(),
                                          json::array({{{"type", "GeneralizedCylinder"}, {"caps", "flat"}, {"sides", 10}}})));
  const TriangleMesh& mesh = skinOf(l).mesh();
  // The rims duplicate the end rings (crisp cap edges): open without welding, closed with it.
  EXPECT_FALSE(test::checkClosedManifold(mesh).closed);
  expectClosedOrientedManifold(mesh, 1e-12);
}

TEST(GeneralizedCylinder, ACutThreadIsSkinnedAsOneClosedTubePerStrand) {
  // A thread cut in two (Scene::cut): two tubes, each a closed oriented manifold capped at the
  // cut, and no triangle between them — once strand 2 is lifted by 1 m, every vertex of tube 1
  // stays with strand 1 (below 0.5 m) and every vertex of tube 2 with strand 2.
  Loaded l = load(test::splineScene(test::planarWave(), json::array({{{"type", "GeneralizedCylinder"}, {"sides", 12}}})));
  CurveBody& thread = *l.scene->bodies()[0]->curve();
  l.scene->cut(thread, 0.4);
  l.visuals->update(l.scene->state());
  const GeneralizedCylinderModel& skin = skinOf(l);
  ASSERT_EQ(skin.meshCount(), 2);
  for (int k = 0; k < 2; ++k) expectClosedOrientedManifold(skin.mesh(k));
  // Rings follow the rest length: the strands share them in proportion (at least 2 each).
  EXPECT_GE(skin.axis(0).rows(), 2);
  EXPECT_GE(skin.axis(1).rows(), 2);
  BasisRow right;
  thread.basis().evaluate(thread.basis().cuts().at(0), right);
  SceneState s = l.scene->state();
  auto q = thread.block(s.q);
  for (int i = right.first; i < thread.pointCount(); ++i) q(i, 2) += 1.0;
  l.visuals->update(s);
  // Planar wave: |z| <= its amplitude plus the skin radius, well below 0.5 m.
  EXPECT_LT(skin.mesh(0).vertices.col(2).maxCoeff(), 0.5);
  EXPECT_GT(skin.mesh(1).vertices.col(2).minCoeff(), 0.5);
}

TEST(GeneralizedCylinder, VerticesLieAtTheRequestedRadiusFromTheAxis) {
  // A varying radius profile (a bulge) on a helix: each ring's vertices at r(u_k) from x_k,
  // each cap vertex at the end radius from the end point.
  const json profile = json::array({json::array({0.0, 2e-3}), json::array({0.4, 2e-3}), json::array({0.5, 5e-3}),
                                    json::array({0.6, 2e-3}), json::array({1.0, 1e-3})});
  const Loaded l = load(test::splineScene(
      test::helix(), json::array({{{"type", "GeneralizedCylinder"}, {"radius_profile", profile}, {"samples", 80}}})));
  const GeneralizedCylinderModel& skin = skinOf(l);
  const GeneralizedCylinder& c = skin.cylinder();
  const TriangleMesh& mesh = c.mesh();
  double worst = 0.0;
  for (int k = 0; k < c.rings(); ++k) {
    const double u = static_cast<double>(k) / (c.rings() - 1);
    const double r = skin.profile().radius(u);
    EXPECT_DOUBLE_EQ(skin.radii()[k], r);
    for (int j = 0; j < c.sides(); ++j)
      worst = std::max(worst, std::abs((mesh.vertices.row(c.sideVertex(k, j)) - skin.axis().row(k)).norm() - r));
  }
  // Cap vertices (everything after the side rings) at the end radius from the end points.
  const Vec3 start = skin.axis().row(0).transpose(), end = skin.axis().row(c.rings() - 1).transpose();
  for (int v = c.rings() * c.sides(); v < mesh.vertexCount(); ++v) {
    const Vec3 x = mesh.vertices.row(v).transpose();
    const double to_start = std::abs((x - start).norm() - skin.radii()[0]);
    const double to_end = std::abs((x - end).norm() - skin.radii()[c.rings() - 1]);
    worst = std::max(worst, std::min(to_start, to_end));
  }
  EXPECT_LE(worst, 1e-9);
  expectClosedOrientedManifold(mesh);
}

TEST(GeneralizedCylinder, ARodsSpansGiveItsDefaultSkinTheirRadii) {
  // A FramedChain whose last quarter is a thin tip ("spans"): without a radius of its own, the
  // skin takes the body's radius at every node (the larger side's at the step) and every
  // segment's middle, joined by the profile's monotone cubic — the shaft's radius up to the node
  // of the step, a taper over the first half of the tip's first segment, no overshoot.
  const double shaft = 1e-3, tip = 4e-4, kEpsilon = std::numeric_limits<double>::epsilon();
  const json document = test::rodWithThinTip(0.2, 21, shaft, 0.75, tip, json::array({{{"type", "GeneralizedCylinder"}}}));
  const Loaded l = load(document);
  const RadiusProfile& profile = skinOf(l).profile();
  // Segments of 1 cm (u steps of 0.05): the step's node at u = 0.75, the tip's first middle at 0.775.
  for (int k = 0; k <= 1000; ++k) {
    const double u = k / 1000.0, r = profile.radius(u);
    if (u <= 0.75) {
      EXPECT_DOUBLE_EQ(r, shaft) << "u = " << u;
    }
    if (u >= 0.775) {
      EXPECT_DOUBLE_EQ(r, tip) << "u = " << u;
    }
    // (Between equal knots the cubic's weights sum to 1 within a few ulps.)
    EXPECT_LE(r, shaft * (1.0 + 4.0 * kEpsilon)) << "u = " << u;
    EXPECT_GE(r, tip * (1.0 - 4.0 * kEpsilon)) << "u = " << u;
  }
  EXPECT_DOUBLE_EQ(profile.maxRadius(), shaft);
}

TEST(GeneralizedCylinder, RingsSitAtEqualArcLengthOnTheRestCurve) {
  const Loaded l = load(test::splineScene(test::planarWave(), json::array({{{"type", "GeneralizedCylinder"}, {"samples", 40}}})));
  const GeneralizedCylinderModel& skin = skinOf(l);
  const auto& spline = *l.scene->bodies().front()->curve();
  const geometry::ArcLengthParameterization arc(spline.basis(), spline.initialPositions());
  const std::vector<double>& s = skin.mapping().abscissas();
  for (std::size_t k = 0; k < s.size(); ++k)
    EXPECT_NEAR(arc.lengthAt(s[k]), arc.totalLength() * k / (s.size() - 1), 1e-12);
}

TEST(GeneralizedCylinder, FramesDoNotTwistOnAPlanarCurve) {
  // On a curve in the xy-plane the rotation-minimizing frame keeps its normal on the plane's
  // normal: with N_0 = z, every N_k = z and every B_k lies in the plane. A Frenet frame would
  // flip at each inflection of the wave.
  const Loaded l = load(test::splineScene(test::planarWave(20, 0.015), json::array({{{"type", "GeneralizedCylinder"}}})));
  const GeneralizedCylinder& c = skinOf(l).cylinder();
  ASSERT_EQ(static_cast<int>(c.frames().size()), c.rings());
  for (const geometry::CurveFrame& f : c.frames()) {
    EXPECT_NEAR(f.normal.z(), 1.0, 1e-12);
    EXPECT_NEAR(f.binormal.z(), 0.0, 1e-12);
    EXPECT_NEAR(f.tangent.z(), 0.0, 1e-12);
  }
  // Vertex j = 0 of every ring therefore lies straight above the axis: x_k + r z.
  const GeneralizedCylinderModel& skin = skinOf(l);
  for (int k = 0; k < c.rings(); ++k)
    EXPECT_LE((c.mesh().vertices.row(c.sideVertex(k, 0)) - skin.axis().row(k) - skin.radii()[k] * Vec3::UnitZ().transpose())
                  .norm(),
              1e-12);
}

TEST(GeneralizedCylinder, NormalsAreUnitOutwardAndPerpendicularToTheSurface) {
  const json profile = json::array({json::array({0.0, 2e-3}), json::array({0.5, 5e-3}), json::array({1.0, 2e-3})});
  const Loaded l = load(test::splineScene(
      test::planarWave(), json::array({{{"type", "GeneralizedCylinder"}, {"radius_profile", profile}, {"samples", 200}}})));
  const GeneralizedCylinderModel& skin = skinOf(l);
  const GeneralizedCylinder& c = skin.cylinder();
  const TriangleMesh& mesh = c.mesh();
  for (int v = 0; v < mesh.vertexCount(); ++v) EXPECT_NEAR(mesh.normals.row(v).norm(), 1.0, 1e-12);
  // Side normals: outward (away from the axis) and orthogonal, up to O(h²), to the meridian
  // chord v_{k+1,j} − v_{k−1,j}, which includes the radius slope r'.
  double worst = 0.0;
  for (int k = 1; k + 1 < c.rings(); ++k)
    for (int j = 0; j < c.sides(); ++j) {
      const Vec3 n = mesh.normals.row(c.sideVertex(k, j)).transpose();
      const Vec3 radial = (mesh.vertices.row(c.sideVertex(k, j)) - skin.axis().row(k)).transpose();
      EXPECT_GT(n.dot(radial), 0.0);
      const Vec3 meridian = (mesh.vertices.row(c.sideVertex(k + 1, j)) - mesh.vertices.row(c.sideVertex(k - 1, j))).transpose();
      worst = std::max(worst, std::abs(n.dot(meridian.normalized())));
    }
  // Measured 5.9e-3: the chord spans 2 ring spacings (1.3 mm) where the inside of the bend has a
  // radius of curvature of ~1.3 mm (r κ up to 0.8). Without the curvature term (1 − r d·κ) of
  // the normal the same check gives 0.10.
  EXPECT_LE(worst, 1e-2);
}

TEST(GeneralizedCylinder, UpdateFollowsTheControlPoints) {
  Loaded l = load(test::splineScene(test::planarWave(), json::array({{{"type", "GeneralizedCylinder"}}})));
  const GeneralizedCylinderModel& skin = skinOf(l);
  const Points before = skin.mesh().vertices;
  // A rigid translation of the control points translates the skin exactly (Σ b_i = 1).
  SceneState s = l.scene->state();
  for (Eigen::Index i = 0; i < s.q.size(); i += 3) s.q[i + 1] += 0.25;
  l.visuals->update(s);
  EXPECT_LE(((skin.mesh().vertices - before).rowwise() - Vec3(0, 0.25, 0).transpose()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(GeneralizedCylinder, RebindsToABodyWhosePointsWereInsertedAndKeepsItsAxis) {
  // Scene::refine inserts two control points into the helix (its curve unchanged); the visual
  // scene sees the new layout revision at its next update and rebuilds the skin's mapping on the
  // refined basis. Same curve, same rest curve: the rings sit at the same abscissas (equal arc
  // length, computed anew on the refined pieces to ArcLengthParameterization's relative tolerance
  // 1e-12, ~1e-13 m over the helix's 0.2 m) and so on the same axis points (bound 1e-10 m).
  const Loaded l = load(test::splineScene(test::helix(), json::array({{{"type", "GeneralizedCylinder"}, {"samples", 40}}})));
  const Points axis = skinOf(l).axis();
  CurveBody* curve = l.scene->bodies().front()->curve();
  const int points = curve->pointCount();
  l.scene->refine(*curve, {0.3, 0.7});
  ASSERT_EQ(curve->pointCount(), points + 2);
  l.visuals->update(l.scene->state());
  ASSERT_EQ(skinOf(l).axis().rows(), axis.rows());
  EXPECT_LE((skinOf(l).axis() - axis).cwiseAbs().maxCoeff(), 1e-10);
  expectClosedOrientedManifold(skinOf(l).mesh());
}

TEST(SplineAxisMapping, PassesTheGenericMappingTest) {
  const geometry::UniformCubicBSpline basis(12);
  std::vector<double> s;
  for (int k = 0; k <= 30; ++k) s.push_back(k / 30.0);
  const SplineAxisMapping mapping(basis, s);
  test::expectMappingConsistent(mapping, test::randomPoints(12, 0.1, 7), 1e-6, 1e-9);
  // Derivatives: W' q against central differences of P(s) in s.
  const Points q = test::randomPoints(12, 0.1, 3);
  Points d(31, 3), plus(1, 3), minus(1, 3);
  mapping.applyDerivative(q, d);
  for (int k = 1; k < 30; ++k) {
    const double h = 1e-6;
    SplineAxisMapping(basis, {s[k] + h}).apply(q, plus);
    SplineAxisMapping(basis, {s[k] - h}).apply(q, minus);
    EXPECT_LE((d.row(k) - (plus - minus) / (2 * h)).norm(), 1e-6 * (1.0 + d.row(k).norm()));
  }
}

TEST(RadiusProfile, IsMonotoneBetweenKnotsAndItsSlopeIsItsDerivative) {
  const RadiusProfile p({0.0, 0.3, 0.5, 0.55, 1.0}, {1e-3, 1e-3, 4e-3, 4e-3, 0.5e-3});
  for (int k = 0; k < 1000; ++k) {
    const double u = k / 1000.0;
    const double r = p.radius(u);
    EXPECT_GE(r, 0.5e-3 - 1e-15);
    EXPECT_LE(r, 4e-3 + 1e-15);
    if (u > 0.001 && u < 0.999 && std::abs(u - 0.3) > 2e-6 && std::abs(u - 0.5) > 2e-6 && std::abs(u - 0.55) > 2e-6) {
      const double h = 1e-7;
      EXPECT_NEAR(p.slope(u), (p.radius(u + h) - p.radius(u - h)) / (2 * h), 1e-5);
    }
  }
  EXPECT_DOUBLE_EQ(p.radius(0.4), p.radius(0.4));
  EXPECT_DOUBLE_EQ(p.radius(0.52), 4e-3);  // flat between equal knots: no overshoot
}

TEST(GeneralizedCylinder, BadParametersNameTheFileAndPath) {
  const auto message = [](const json& component) {
    try {
      load(test::splineScene(test::planarWave(), json::array({component})));
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({{"type", "GeneralizedCylinder"}, {"caps", "pointy"}}).find("/nodes/0/components/1/caps"), std::string::npos);
  EXPECT_NE(message({{"type", "GeneralizedCylinder"}, {"radius", -1}}).find("/nodes/0/components/1/radius"), std::string::npos);
  EXPECT_NE(message({{"type", "GeneralizedCylinder"}, {"radius_profile", json::array({json::array({0.5, 1e-3}), json::array({0.2, 1e-3})})}})
                .find("radius_profile"),
            std::string::npos);
  EXPECT_NE(message({{"type", "GeneralizedCylinder"}, {"color", {2, 0, 0}}}).find("/color"), std::string::npos);
  EXPECT_NE(message({{"type", "GeneralizedCylinder"}, {"sides", 2}}).find("/sides"), std::string::npos);
}

TEST(VisualScene, AddsADefaultSkinToSplinesNothingDraws) {
  const Loaded l = load(test::splineScene(test::planarWave(), json::array()));
  ASSERT_EQ(l.visuals->models().size(), 1u);
  EXPECT_EQ(l.visuals->modelName(0), "thread_skin");
  EXPECT_DOUBLE_EQ(skinOf(l).radii()[0], 2e-3);  // the spline's radius
}

}  // namespace
}  // namespace filum::visual
