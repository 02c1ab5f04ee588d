// A vessel segmented from a scan is an open surface mesh (open at its inlet and outlets) and a
// lumen: TriangleMeshObstacle with "side": "inside" takes it, finds its inner side from the faces'
// winding, and tells the sides of a point by the angle-weighted pseudo-normal of the closest
// feature. Checked against independent answers: the winding number on a closed mesh, the exact
// distance over every triangle and the tube's own geometry on an open one, and Coulomb's law for a
// rod sliding down an inclined segmented tube (the same test as the centreline lumen's,
// vessel_lumen_test.cpp), which never sinks into the wall by more than a tenth of its radius.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "collision_scenes.hpp"
#include "inclined_tube_slide.hpp"
#include "support/closest_on_triangle.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"

#ifdef FILUM_WITH_CGAL
#include "filum/collision/triangle_mesh_obstacle.hpp"
#include "filum/collision/triangle_mesh_surface.hpp"
#endif

namespace filum::collision {
namespace {

#ifdef FILUM_WITH_CGAL

constexpr double kTube = 5e-3;    // m, the circle the tube's vertices lie on
constexpr int kSides = 48;        // faces around; each face's centre line is at kTube cos(π/kSides)
constexpr double kTubeLength = 0.3;
constexpr int kRings = 30;

/// An open polygonal tube along `axis` through the origin, no caps: a segmented vessel. Its faces
/// are centred at the angles 2πk/kSides from `down`, so a rod lying along the bottom lies on the
/// centre line of one flat face. `outward`: faces wound counter-clockwise seen from outside.
struct Tube {
  Points vertices;
  std::vector<std::array<int, 3>> triangles;
};
Tube makeTube(const Vec3& axis, const Vec3& down, bool outward) {
  const Vec3 side = axis.cross(down);
  Tube t;
  t.vertices.resize((kRings + 1) * kSides, 3);
  for (int j = 0; j <= kRings; ++j)
    for (int k = 0; k < kSides; ++k) {
      const double theta = (2 * k + 1) * M_PI / kSides;
      const Vec3 x = (-0.5 + double(j) / kRings) * kTubeLength * axis + kTube * (std::cos(theta) * down + std::sin(theta) * side);
      t.vertices.row(j * kSides + k) = x.transpose();
    }
  for (int j = 0; j < kRings; ++j)
    for (int k = 0; k < kSides; ++k) {
      const int a = j * kSides + k, b = (j + 1) * kSides + k, c = (j + 1) * kSides + (k + 1) % kSides,
                d = j * kSides + (k + 1) % kSides;
      // (a, b, c) runs along the axis then round it: axis × tangent points inwards.
      if (outward) {
        t.triangles.push_back({a, c, b});
        t.triangles.push_back({a, d, c});
      } else {
        t.triangles.push_back({a, b, c});
        t.triangles.push_back({a, c, d});
      }
    }
  return t;
}

/// Writes the tube as an ASCII STL (in `unit` metres per file unit) or an OBJ; returns the path.
std::string writeTube(const Tube& t, const std::string& name, double unit) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream out(path);
  out.precision(17);
  const auto vertex = [&](int i) -> Vec3 {  // evaluated, not an expression over a temporary
    const Vec3 x = t.vertices.row(i).transpose();
    return x / unit;
  };
  if (name.size() > 4 && name.substr(name.size() - 4) == ".stl") {
    out << "solid tube\n";
    for (const auto& f : t.triangles) {
      out << "facet normal 0 0 0\nouter loop\n";
      for (int c = 0; c < 3; ++c) out << "vertex " << vertex(f[c]).x() << ' ' << vertex(f[c]).y() << ' ' << vertex(f[c]).z() << '\n';
      out << "endloop\nendfacet\n";
    }
    out << "endsolid tube\n";
  } else {
    for (int i = 0; i < t.vertices.rows(); ++i) out << "v " << vertex(i).x() << ' ' << vertex(i).y() << ' ' << vertex(i).z() << '\n';
    for (const auto& f : t.triangles) out << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
  }
  return path;
}

std::unique_ptr<TriangleMeshObstacle> lumenFromFile(const std::string& path, const std::string& units) {
  const nlohmann::json component = {{"type", "TriangleMeshObstacle"}, {"file", path}, {"units", units}, {"side", "inside"}};
  return TriangleMeshObstacle::fromParams(Params(component, "lumen.json", "/nodes/0/components/0"));
}

TEST(OpenLumenMesh, ThePseudoNormalsSideIsTheWindingNumbersOnAClosedMesh) {
  // Bærentzen & Aanæs: on a closed mesh, sign((x − c)·n) with n the angle-weighted pseudo-normal
  // of c's feature is the inside test, whether c is inside a face, on an edge or at a vertex.
  const auto mesh = TriangleMeshSurface::read(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/data/organ.off");
  std::mt19937 rng(11);
  const Eigen::AlignedBox3d box = mesh->bounds();
  std::uniform_real_distribution<double> u(-0.7, 0.7);
  int inside = 0, on_edge_or_vertex = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const Vec3 x = box.center() + box.sizes().cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
    const TriangleMeshSurface::ClosestFeature c = mesh->closestFeature(x);
    const bool by_pseudo_normal = (x - c.point).dot(c.normal) < 0.0;
    const double w = test::windingNumber(mesh->vertices(), mesh->triangles(), x);
    ASSERT_TRUE(std::abs(w) < 1e-6 || std::abs(w - 1.0) < 1e-6) << w;  // a closed mesh: 0 or 1 to round-off
    EXPECT_EQ(by_pseudo_normal, w > 0.5) << "trial " << trial;
    EXPECT_FALSE(c.on_border);
    inside += w > 0.5;
    const Vec3 face = mesh->nearestFaceNormal(x);
    on_edge_or_vertex += (c.normal - face).norm() > 1e-9;
  }
  EXPECT_GT(inside, 100);
  EXPECT_GT(on_edge_or_vertex, 50);  // the edge and vertex normals were exercised, not only faces'
}

TEST(OpenLumenMesh, ThePseudoNormalOfAnEdgeOrACornerIsTheAngleWeightedSumOfItsFaces) {
  // A cube of half side h, two triangles a face, wound outwards. A point off an edge projects onto
  // the edge: its pseudo-normal is (n1 + n2)/|n1 + n2| of the two faces; off a corner, the three
  // faces meet at right angles, each weighted π/2 (its one or two triangles' angles there):
  // (1, 1, 1)/√3; off a face, the face's normal. A wrong edge or corner taken from the closest
  // face's barycentric coordinates gives another of these normals.
  const double h = 0.01;
  Points v(8, 3);
  for (int i = 0; i < 8; ++i) v.row(i) << (i & 1 ? h : -h), (i & 2 ? h : -h), (i & 4 ? h : -h);
  const std::vector<std::array<int, 3>> quads = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                                                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  const TriangleMeshSurface cube(v, quads);
  double scale = 0.0;
  ASSERT_GT(cube.enclosedVolume(scale), 0.0) << "the cube is wound outwards";
  struct Case {
    Vec3 x, normal;
  };
  const std::vector<Case> cases = {
      {Vec3(1.2, 1.2, 0.3) * h, Vec3(1, 1, 0).normalized()},     // off the edge x = y = h
      {Vec3(-1.1, 0.2, -1.3) * h, Vec3(-1, 0, -1).normalized()},  // off the edge x = z = −h
      {Vec3(1.3, -1.2, 1.1) * h, Vec3(1, -1, 1).normalized()},    // off a corner
      {Vec3(-1.2, -1.4, -1.1) * h, Vec3(-1, -1, -1).normalized()},
      {Vec3(1.5, 0.2, 0.3) * h, Vec3(1, 0, 0)},                   // off a face
      {Vec3(0.1, 0.3, 0.8) * h, Vec3(0, 0, 1)},                   // inside, nearest the top face
  };
  for (const Case& c : cases) {
    const TriangleMeshSurface::ClosestFeature f = cube.closestFeature(c.x);
    EXPECT_NEAR((f.normal - c.normal).norm(), 0.0, 1e-12) << c.x.transpose() / h << ": " << f.normal.transpose();
    EXPECT_EQ((c.x - f.point).dot(f.normal) < 0.0, cube.inside(c.x)) << c.x.transpose() / h;
  }
}

TEST(OpenLumenMesh, AnOpenTubeIsALumenWhicheverWayItsFacesAreWound) {
  const Vec3 axis = Vec3(1, 0, 0), down = Vec3(0, 0, -1), side = axis.cross(down);
  const double inscribed = kTube * std::cos(M_PI / kSides);
  const double max_distance = 1e-3;
  for (const bool outward : {true, false}) {
    const Tube tube = makeTube(axis, down, outward);
    for (const std::string& name : {std::string("filum_open_tube.stl"), std::string("filum_open_tube.obj")}) {
      const std::string what = name + (outward ? " wound outwards" : " wound inwards");
      const auto lumen = lumenFromFile(writeTube(tube, name, 1e-3), "mm");
      ASSERT_FALSE(lumen->surface().closed()) << what;
      std::mt19937 rng(5);
      std::uniform_real_distribution<double> along(-0.4, 0.4), angle(0.0, 2 * M_PI), depth(0.0, 0.9 * max_distance);
      for (int trial = 0; trial < 300; ++trial) {
        const double s = along(rng) * kTubeLength, theta = angle(rng);
        const Vec3 radial = std::cos(theta) * down + std::sin(theta) * side;
        // Inside, within max_distance of the wall: `depth` from the circle through the faces' centre
        // lines, so at most depth + inscribed (1 − cos(π/kSides)) = depth + 11 µm from a face.
        const Vec3 in = s * axis + (inscribed - depth(rng)) * radial;
        SurfaceSample sample;
        ASSERT_TRUE(lumen->sample(in, max_distance, sample)) << what;
        // Positive clear of the wall: the exact distance over every triangle (Ericson's closed
        // form), to a few ulps of the 0.15 m coordinates (ε · 0.15 m = 3e-17 m per operation).
        EXPECT_NEAR(sample.distance, test::exactDistance(lumen->surface().vertices(), lumen->surface().triangles(), in),
                    1e-14)
            << what;
        EXPECT_GT(sample.normal.dot(-radial), 0.9) << what << ": the normal points into the lumen";
        // Through the wall by less than max_distance: negative, pushed back in.
        const Vec3 out = s * axis + (kTube + depth(rng)) * radial;
        ASSERT_TRUE(lumen->sample(out, max_distance + kTube - inscribed, sample)) << what;
        EXPECT_LT(sample.distance, 0.0) << what;
        EXPECT_GT(sample.normal.dot(-radial), 0.9) << what;
      }
      // Far outside the wall (an instrument outside the vessel) and beyond the open ends: free.
      SurfaceSample sample;
      EXPECT_FALSE(lumen->sample(3 * kTube * side, max_distance, sample)) << what;
      EXPECT_FALSE(lumen->sample((0.5 * kTubeLength + 2 * max_distance) * axis, max_distance, sample)) << what;
      // Next to the rim of an opening, from outside the vessel: the rim is a thin edge, so the
      // point is clear of it (d > 0) and pushed away from it, not through the wall into the lumen.
      const Vec3 rim = 0.5 * kTubeLength * axis + kTube * std::cos(M_PI / kSides) * down;  // an edge's middle
      const Vec3 beside = rim + 0.5 * max_distance * (axis + down).normalized();
      ASSERT_TRUE(lumen->sample(beside, max_distance, sample)) << what;
      EXPECT_NEAR(sample.distance, 0.5 * max_distance, 1e-12) << what;
      EXPECT_GT(sample.normal.dot((axis + down).normalized()), 0.999) << what;
      // Far inside: no contact.
      EXPECT_FALSE(lumen->sample(Vec3::Zero(), max_distance, sample)) << what;
    }
  }
}

TEST(OpenLumenMesh, AMeshThatEnclosesNoVolumeHasNoInnerSideAndIsRefused) {
  const std::string path = (std::filesystem::temp_directory_path() / "filum_sheet.obj").string();
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
  try {
    lumenFromFile(path, "mm");
    ADD_FAILURE() << "a flat sheet was taken as a lumen";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("lumen.json: /nodes/0/components/0/file"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("encloses a volume"), std::string::npos) << e.what();
  }
}

constexpr double kRod = test::kSlideRodRadius;

struct SlideRun {
  double displacement = 0.0;       // m, of the rod's middle down the slope
  double worst_penetration = 0.0;  // m, deepest a point of the centre line came within r of the wall
};

SlideRun slide(double alpha, double mu, double duration) {
  // The tube's faces centred on its bottom line: the rod lies on one flat face strip.
  const double inscribed = kTube * std::cos(M_PI / kSides);
  const auto lumen = [](const test::InclinedTube& tube) {
    const std::string file = writeTube(makeTube(tube.axis, tube.down, false), "filum_inclined_tube.stl", 1e-3);
    return nlohmann::json{{"type", "TriangleMeshObstacle"}, {"file", file}, {"units", "mm"}, {"side", "inside"}};
  };
  SlideRun run;
  run.displacement = test::slideDownInclinedTube(alpha, mu, duration, inscribed, lumen, [&](const Scene& scene) {
    const CurveBody& rod = *scene.bodies()[0]->curve();
    const auto& mesh = dynamic_cast<const TriangleMeshObstacle&>(*test::pipelineOf(scene).obstacles()[0]);
    for (int i = 0; i <= 50; ++i) {
      const Vec3 x = rod.position(scene.state().q, i / 50.0);
      const double clearance = (x - mesh.surface().closestPoint(x)).norm();  // the centre line stays inside
      run.worst_penetration = std::max(run.worst_penetration, kRod - clearance);
    }
  });
  return run;
}

TEST(OpenLumenMesh, RodSlidesDownAnInclinedSegmentedTubeWithCoulombsAcceleration) {
  // The rod lies along the centre of one flat face strip: a plane with Coulomb friction, so
  // a = g (sin α − μ cos α) and d = ½ a t². Implicit Euler's positions under a constant acceleration
  // are a h² n(n + 1)/2: 1/n = 0.5 % long after n = 200 steps; a start one step late would make it
  // 1 % short: within [−1 %, +0.5 %], asked within 1.5 % (as for the centreline lumen).
  const double alpha = M_PI / 6, mu = 0.3, t = 0.2;
  const SlideRun run = slide(alpha, mu, t);
  const double expected = 0.5 * test::kSlideGravity * (std::sin(alpha) - mu * std::cos(alpha)) * t * t;
  std::printf("  slid %.3f mm, Coulomb %.3f mm; deepest %.4f of r\n", 1e3 * run.displacement, 1e3 * expected,
              run.worst_penetration / kRod);
  EXPECT_NEAR(run.displacement, expected, 0.015 * expected);
  EXPECT_LT(run.worst_penetration, 0.1 * kRod);
}

TEST(OpenLumenMesh, RodHeldByFrictionInASegmentedTubeBelowTheAngleOfFriction) {
  // tan 30° < μ = 0.7: static, up to the friction rows' compliance creep (< 1 µm, as for the
  // centreline lumen); asked below 10 µm.
  const SlideRun run = slide(M_PI / 6, 0.7, 0.2);
  EXPECT_LT(std::abs(run.displacement), 1e-5);
  EXPECT_LT(run.worst_penetration, 0.1 * kRod);
}

#endif  // FILUM_WITH_CGAL

}  // namespace
}  // namespace filum::collision
