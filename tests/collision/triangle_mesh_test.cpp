// Triangle-mesh obstacles (CGAL): the distance of a thread sphere to the organ mesh of
// apps/scenes/organ.json matches the exact closest point over every triangle, the inside test
// matches the winding number, the four file formats read the same surface, and scene errors
// name the file and JSON place. Without FILUM_WITH_CGAL a scene naming the mesh obstacle gets
// an error naming the option.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "filum/all_components.hpp"
#include "filum/collision/register_components.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "support/closest_on_triangle.hpp"

#ifdef FILUM_WITH_CGAL
#include "filum/collision/contact_pipeline.hpp"
#include "filum/collision/triangle_mesh_obstacle.hpp"
#include "filum/collision/triangle_mesh_surface.hpp"
#endif

namespace filum::collision {
namespace {

const std::string kOrgan = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/data/organ.off";

#ifdef FILUM_WITH_CGAL

TEST(TriangleMeshSurface, ClosestPointAndInsideMatchExactReferences) {
  const auto mesh = TriangleMeshSurface::read(kOrgan);
  ASSERT_EQ(mesh->vertexCount(), 642);
  ASSERT_EQ(mesh->triangleCount(), 1280);
  // The mesh is oriented outwards: the winding number at its centre is +1.
  EXPECT_NEAR(test::windingNumber(mesh->vertices(), mesh->triangles(), Vec3::Zero()), 1.0, 1e-9);

  std::mt19937 rng(3);
  const Eigen::AlignedBox3d box = mesh->bounds();
  std::uniform_real_distribution<double> u(-1.3, 1.3);
  int inside_count = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Vec3 x = box.center() + 0.5 * box.sizes().cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
    // Exact reference: the closest point over all 1280 triangles.
    double best = std::numeric_limits<double>::infinity();
    for (const auto& t : mesh->triangles()) {
      const Vec3 c = test::closestOnTriangle(x, mesh->vertices().row(t[0]).transpose(), mesh->vertices().row(t[1]).transpose(),
                                       mesh->vertices().row(t[2]).transpose());
      best = std::min(best, (x - c).norm());
    }
    // CGAL's AABB tree returns the same distance to round-off (a few ulps of the 0.1 m size).
    const double cgal = (x - mesh->closestPoint(x)).norm();
    EXPECT_NEAR(cgal, best, 1e-14) << "trial " << trial;
    // Inside test against the winding number (1 inside, 0 outside, exactly up to round-off).
    const double w = test::windingNumber(mesh->vertices(), mesh->triangles(), x);
    ASSERT_TRUE(std::abs(w) < 1e-6 || std::abs(w - 1.0) < 1e-6) << w;
    EXPECT_EQ(mesh->inside(x), w > 0.5) << "trial " << trial;
    inside_count += w > 0.5;
  }
  EXPECT_GT(inside_count, 50);
  EXPECT_LT(inside_count, 350);
}

TEST(TriangleMeshObstacle, SphereToMeshGapIsTheExactSignedDistanceMinusTheRadius) {
  const auto surface = std::shared_ptr<const TriangleMeshSurface>(TriangleMeshSurface::read(kOrgan));
  const TriangleMeshObstacle obstacle(surface);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double r = 1e-3;  // a thread sphere of 1 mm
  for (int trial = 0; trial < 200; ++trial) {
    // Points near the surface: a vertex pushed along a random direction by up to 3 mm.
    const int v = trial * 3 % surface->vertexCount();
    const Vec3 x = surface->vertices().row(v).transpose() + 3e-3 * Vec3(u(rng), u(rng), u(rng));
    SurfaceSample sample;
    ASSERT_TRUE(obstacle.sample(x, 1.0, sample));
    const double best = test::exactDistance(surface->vertices(), surface->triangles(), x);
    const double sign = test::windingNumber(surface->vertices(), surface->triangles(), x) > 0.5 ? -1.0 : 1.0;
    EXPECT_NEAR(sample.distance - r, sign * best - r, 1e-14);
    EXPECT_NEAR((sample.point - x).norm(), best, 1e-14);
    // The normal points from the surface towards the outside: x = point + d n.
    EXPECT_LT((sample.point + sample.distance * sample.normal - x).norm(), 1e-12);
  }
}

TEST(TriangleMeshObstacle, ACavityIsTheSameSurfaceSeenFromInside) {
  // "side": "inside": the distance is the exact one with the opposite sign (positive inside, where
  // the bodies are free), the normal points into the cavity (x = point + d n), and points far
  // inside give no contact while points outside — escaped through the wall — always do. The side
  // comes from the nearest face's normal or the exact test: both agree with the winding number.
  const auto surface = std::shared_ptr<const TriangleMeshSurface>(TriangleMeshSurface::read(kOrgan));
  const TriangleMeshObstacle cavity(surface, true);
  EXPECT_TRUE(cavity.cavity());
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double max_distance = 2e-3;
  int inside_far = 0, outside = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // Near the surface (a vertex pushed by up to 3 mm), or anywhere in the box around it (2 cm more).
    const int v = trial * 7 % surface->vertexCount();
    const Eigen::AlignedBox3d& box = surface->bounds();
    const Vec3 x = trial % 2 == 0 ? Vec3(surface->vertices().row(v).transpose() + 3e-3 * Vec3(u(rng), u(rng), u(rng)))
                                  : Vec3(box.center() + 0.5 * (box.sizes() + Vec3::Constant(0.04)).cwiseProduct(
                                                             Vec3(u(rng), u(rng), u(rng))));
    const double best = test::exactDistance(surface->vertices(), surface->triangles(), x);
    const bool inside = test::windingNumber(surface->vertices(), surface->triangles(), x) > 0.5;
    SurfaceSample sample;
    const bool hit = cavity.sample(x, max_distance, sample);
    if (inside && best > max_distance) {
      EXPECT_FALSE(hit) << "far inside the cavity, at " << best << " m from its wall";
      ++inside_far;
      continue;
    }
    ASSERT_TRUE(hit);
    outside += inside ? 0 : 1;
    EXPECT_NEAR(sample.distance, inside ? best : -best, 1e-14);
    EXPECT_LT((sample.point + sample.distance * sample.normal - x).norm(), 1e-12);
  }
  EXPECT_GT(inside_far, 10);  // both kinds of point were met
  EXPECT_GT(outside, 10);
}

TEST(TriangleMeshSurface, ReadsOffObjStlAndPlyAlike) {
  const auto off = TriangleMeshSurface::read(kOrgan);
  const auto dir = std::filesystem::temp_directory_path() / "filum_mesh_formats";
  std::filesystem::create_directories(dir);
  const Points& V = off->vertices();
  const auto& F = off->triangles();
  {
    std::ofstream obj(dir / "organ.obj");
    obj.precision(17);
    for (int v = 0; v < V.rows(); ++v) obj << "v " << V(v, 0) << ' ' << V(v, 1) << ' ' << V(v, 2) << '\n';
    for (const auto& t : F) obj << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  }
  {
    std::ofstream ply(dir / "organ.ply");
    ply.precision(17);
    ply << "ply\nformat ascii 1.0\nelement vertex " << V.rows() << "\nproperty double x\nproperty double y\n"
        << "property double z\nelement face " << F.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (int v = 0; v < V.rows(); ++v) ply << V(v, 0) << ' ' << V(v, 1) << ' ' << V(v, 2) << '\n';
    for (const auto& t : F) ply << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  }
  {
    std::ofstream stl(dir / "organ.stl");
    stl.precision(17);
    stl << "solid organ\n";
    for (const auto& t : F) {
      stl << "facet normal 0 0 0\nouter loop\n";
      for (int c = 0; c < 3; ++c) stl << "vertex " << V(t[c], 0) << ' ' << V(t[c], 1) << ' ' << V(t[c], 2) << '\n';
      stl << "endloop\nendfacet\n";
    }
    stl << "endsolid organ\n";
  }
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-0.06, 0.06);
  for (const char* name : {"organ.obj", "organ.ply", "organ.stl"}) {
    const auto mesh = TriangleMeshSurface::read((dir / name).string());
    EXPECT_EQ(mesh->triangleCount(), off->triangleCount()) << name;
    for (int k = 0; k < 20; ++k) {
      const Vec3 x(u(rng), u(rng), u(rng));
      EXPECT_NEAR((mesh->closestPoint(x) - off->closestPoint(x)).norm(), 0.0, 1e-9) << name;
      EXPECT_EQ(mesh->inside(x), off->inside(x)) << name;
    }
  }
}

TEST(TriangleMeshObstacle, SceneErrorsNameTheFileAndThePlace) {
  nlohmann::json scene = {
      {"name", "mesh errors"},
      {"nodes", {{{"name", "organ"}, {"components", {{{"type", "TriangleMeshObstacle"}, {"file", "no_such_mesh.off"}}}}}}}};
  try {
    loadScene(scene, "mesh.json", app::makeFactory());
    FAIL() << "a missing mesh file was accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("mesh.json: /nodes/0/components/0/file"), std::string::npos) << what;
    EXPECT_NE(what.find("no_such_mesh.off"), std::string::npos) << what;
  }
  // Units of the file: "mm" and the scale multiply; an unknown unit names its JSON path.
  const nlohmann::json in_mm = {{"file", kOrgan}, {"units", "mm"}, {"scale", 2.0}};
  const auto obstacle = TriangleMeshObstacle::fromParams(Params(in_mm, "mesh.json", "/nodes/0/components/0"));
  const auto off = TriangleMeshSurface::read(kOrgan);
  EXPECT_TRUE(obstacle->surface().vertices() == 0.002 * off->vertices());
  scene["nodes"][0]["components"][0]["units"] = "inch";
  try {
    loadScene(scene, "mesh.json", app::makeFactory());
    FAIL() << "an unknown unit was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("mesh.json: /nodes/0/components/0/units"), std::string::npos) << e.what();
  }
  scene["nodes"][0]["components"][0] = {{"type", "TriangleMeshObstacle"}, {"file", "no_such_mesh.off"}};
  // An open mesh (one triangle) is refused: the inside test needs a closed surface.
  const auto dir = std::filesystem::temp_directory_path();
  std::ofstream(dir / "filum_open.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  scene["nodes"][0]["components"][0]["file"] = (dir / "filum_open.off").string();
  try {
    loadScene(scene, "mesh.json", app::makeFactory());
    FAIL() << "an open mesh was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("not closed"), std::string::npos) << e.what();
  }
}

#else

TEST(TriangleMeshObstacle, WithoutCgalASceneNamingItSaysWhichOptionBringsIt) {
  nlohmann::json scene = {
      {"name", "mesh without CGAL"},
      {"nodes", {{{"name", "organ"}, {"components", {{{"type", "TriangleMeshObstacle"}, {"file", "organ.off"}}}}}}}};
  try {
    loadScene(scene, "mesh.json", app::makeFactory());
    FAIL() << "TriangleMeshObstacle exists in a build without CGAL";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("-DFILUM_WITH_CGAL=ON"), std::string::npos) << e.what();
  }
}

#endif

}  // namespace
}  // namespace filum::collision
