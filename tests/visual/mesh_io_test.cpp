// Mesh files: meshes read from files (geometry/mesh_file.hpp, tested on its own in
// tests/geometry/mesh_file_test.cpp) with their normals, OBJ and PLY writers read back, and the
// MeshModel and SphereModel components.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "filum/core/scene_error.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/geometry/mesh_file.hpp"
#include "filum/visual/obj_writer.hpp"
#include "filum/visual/ply_writer.hpp"
#include "filum/visual/sphere_mesh.hpp"
#include "filum/visual/sphere_model.hpp"
#include "filum/visual/visual_scene.hpp"
#include "visual/visual_test_support.hpp"

namespace filum::visual {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

TriangleMesh readMeshFile(const std::string& path) { return triangleMesh(geometry::readMeshFile(path)); }

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(FILUM_BINARY_DIR) / "test_output" / "visual";
  fs::create_directories(dir);
  return dir / name;
}

TEST(MeshFiles, OffTetrahedronIsAClosedOutwardManifold) {
  const TriangleMesh m = readMeshFile(std::string(FILUM_TEST_DATA_DIR) + "/tetrahedron.off");
  EXPECT_EQ(m.vertexCount(), 4);
  EXPECT_EQ(m.triangleCount(), 4);
  const test::ManifoldReport r = test::checkClosedManifold(m);
  EXPECT_TRUE(r.closed && r.consistently_oriented && r.vertex_manifold) << r.first_problem;
  EXPECT_NEAR(test::signedVolume(m), 1.0 / 6.0, 1e-15);
  // Smooth normals at the corner (0,0,0) point away from the solid: (−1, −1, −1) / √3.
  EXPECT_LE((m.normals.row(0) - Vec3(-1, -1, -1).normalized().transpose()).norm(), 1e-12);
}

TEST(MeshFiles, ObjFacesOfAllFormsAndNegativeIndices) {
  const TriangleMesh m = readMeshFile(std::string(FILUM_TEST_DATA_DIR) + "/square_pyramid.obj");
  EXPECT_EQ(m.vertexCount(), 5);
  EXPECT_EQ(m.triangleCount(), 6);  // the quad fans into two
  const test::ManifoldReport r = test::checkClosedManifold(m);
  EXPECT_TRUE(r.closed && r.consistently_oriented) << r.first_problem;
  EXPECT_NEAR(test::signedVolume(m), 4.0 / 3.0, 1e-12);
}

TEST(MeshFiles, ObjAndPlyWritersAreReadBack) {
  TriangleMesh sphere = unitSphere(8);
  sphere.vertices = (0.01 * sphere.vertices).rowwise() + Vec3(0.1, -0.2, 0.3).transpose();
  const fs::path obj = scratch("sphere.obj"), ply = scratch("sphere.ply");
  writeObj(obj.string(), {{"sphere", &sphere}});
  writePly(ply.string(), sphere);
  for (const fs::path& path : {obj, ply}) {
    const TriangleMesh back = readMeshFile(path.string());
    ASSERT_EQ(back.vertexCount(), sphere.vertexCount()) << path;
    ASSERT_EQ(back.triangleCount(), sphere.triangleCount()) << path;
    EXPECT_TRUE(back.triangles == sphere.triangles) << path;
    // 9 significant digits (float precision).
    EXPECT_LE((back.vertices - sphere.vertices).cwiseAbs().maxCoeff(), 1e-9) << path;
  }
}

TEST(MeshFiles, BinaryPlyIsRead) {
  // A binary little-endian PLY with an extra vertex property and a face list of uchar/int.
  const fs::path path = scratch("tetra_binary.ply");
  {
    std::ofstream out(path, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
           "property float z\nproperty uchar red\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
    const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const auto& p : v) {
      out.write(reinterpret_cast<const char*>(p), sizeof p);
      const unsigned char red = 200;
      out.write(reinterpret_cast<const char*>(&red), 1);
    }
    const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (const auto& t : f) {
      const unsigned char n = 3;
      out.write(reinterpret_cast<const char*>(&n), 1);
      out.write(reinterpret_cast<const char*>(t), sizeof t);
    }
  }
  const TriangleMesh m = readMeshFile(path.string());
  EXPECT_EQ(m.vertexCount(), 4);
  EXPECT_EQ(m.triangleCount(), 4);
  EXPECT_DOUBLE_EQ(m.vertices(3, 2), 1.0);
  EXPECT_NEAR(test::signedVolume(m), 1.0 / 6.0, 1e-7);
}

TEST(MeshFiles, ErrorsNameTheFile) {
  const fs::path bad = scratch("bad.obj");
  std::ofstream(bad) << "v 0 0 0\nv 1 0 0\nf 1 2 7\n";
  try {
    readMeshFile(bad.string());
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.obj:3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(readMeshFile(scratch("mesh.stl").string()), std::runtime_error);
}

TEST(MeshModel, ReadsPlacesAndRefusesMissingFiles) {
  // A MeshModel in a node without a body, scaled, rotated 90° about z and moved.
  json scene = test::splineScene(test::planarWave(), json::array());
  const std::string file = std::string(FILUM_TEST_DATA_DIR) + "/tetrahedron.off";
  scene["nodes"].push_back({{"name", "organ"},
                            {"components", json::array({{{"type", "MeshModel"}, {"file", file}, {"scale", 0.01},
                                                         {"rotation", {0, 0, 90}}, {"translation", {0, 0, -0.05}}}})}});
  auto loaded = loadScene(scene, "test", test::visualFactory());
  VisualScene visuals(*loaded);
  visuals.update(loaded->state());
  const TriangleMesh* organ = nullptr;
  for (std::size_t i = 0; i < visuals.models().size(); ++i)
    if (visuals.modelName(i) == "organ_MeshModel") organ = &visuals.models()[i]->mesh();
  ASSERT_NE(organ, nullptr);
  // Vertex (1, 0, 0) → scaled 0.01, turned to (0, 0.01, 0), moved down by 0.05.
  EXPECT_LE((organ->vertices.row(1) - Vec3(0, 0.01, -0.05).transpose()).norm(), 1e-15);
  EXPECT_GT(test::signedVolume(*organ), 0.0);

  // The same file in millimetres: "units" and "scale" multiply.
  scene["nodes"][1]["components"][0]["units"] = "mm";
  auto in_mm = loadScene(scene, "test", test::visualFactory());
  VisualScene visuals_mm(*in_mm);
  visuals_mm.update(in_mm->state());
  for (std::size_t i = 0; i < visuals_mm.models().size(); ++i) {
    if (visuals_mm.modelName(i) == "organ_MeshModel") {
      EXPECT_LE((visuals_mm.models()[i]->mesh().vertices.row(1) - Vec3(0, 1e-5, -0.05).transpose()).norm(), 1e-18);
    }
  }
  scene["nodes"][1]["components"][0]["file"] = "no_such_mesh.off";
  try {
    loadScene(scene, "scene.json", test::visualFactory());
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.json: /nodes/1/components/0/file"), std::string::npos) << e.what();
  }
}

TEST(SphereModel, SpheresFollowTheCurveAConstraintTargetOrStayFixed) {
  const json more = json::array({{{"type", "SphereModel"}, {"name", "evenly"}, {"count", 5}, {"radius", 1e-3}},
                                 {{"type", "SphereModel"}, {"name", "fixed"}, {"center", {0, 0, 0.1}}, {"radius", 2e-3}},
                                 {{"type", "FixedPointConstraint"}, {"name", "hold"}, {"abscissa", 0.25}},
                                 {{"type", "SphereModel"}, {"name", "target"}, {"constraint", "hold"}, {"radius", 1e-3}}});
  json scene = test::splineScene(test::planarWave(), more);
  scene["constraint_solver"] = {{"type", "LagrangeMultiplierSolver"}};
  auto loaded = loadScene(scene, "test", test::visualFactory());
  VisualScene visuals(*loaded);
  visuals.update(loaded->state());
  const auto* evenly = dynamic_cast<const SphereModel*>(visuals.models()[0]);
  const auto* fixed = dynamic_cast<const SphereModel*>(visuals.models()[1]);
  const auto* target = dynamic_cast<const SphereModel*>(visuals.models()[2]);
  ASSERT_TRUE(evenly && fixed && target);
  EXPECT_EQ(evenly->centers().rows(), 5);
  const auto& spline = *loaded->bodies().front()->curve();
  const ConstPointsMap q = spline.block(loaded->state().q);
  EXPECT_LE((evenly->centers().row(0).transpose() - geometry::curvePoint(spline.basis(), q, 0.0)).norm(), 1e-15);
  EXPECT_LE((evenly->centers().row(4).transpose() - geometry::curvePoint(spline.basis(), q, 1.0)).norm(), 1e-15);
  EXPECT_LE((fixed->centers().row(0) - Vec3(0, 0, 0.1).transpose()).norm(), 0.0);
  ASSERT_EQ(target->centers().rows(), 1);
  // Every sphere is a closed manifold with its vertices at the radius from its centre.
  const TriangleMesh& m = fixed->mesh();
  for (int v = 0; v < m.vertexCount(); ++v) EXPECT_NEAR((m.vertices.row(v) - fixed->centers().row(0)).norm(), 2e-3, 1e-15);
  const test::ManifoldReport r = test::checkClosedManifold(m);
  EXPECT_TRUE(r.closed && r.consistently_oriented && r.vertex_manifold && r.euler_characteristic == 2) << r.first_problem;
  EXPECT_NEAR(test::signedVolume(m), 4.0 / 3.0 * 3.141592653589793 * 8e-9, 0.1 * 4.0 / 3.0 * 3.141592653589793 * 8e-9);
  // The default skin is still added: spheres do not draw the body.
  EXPECT_EQ(visuals.models().size(), 4u);
}

TEST(SphereModel, MarksASlidingHoleAndFollowsAScriptedPath) {
  // A needle hole (its target is the initial P(s) of the sliding point) and a probe on a linear
  // path from the origin to (0.1, 0, 0) between t = 0 and t = 1 s: at t = 0.25 s it is at x =
  // 0.025 m (one multiplication by 0.25 and one addition: within a few ulps, 3.5e-18 m each).
  const json more = json::array(
      {{{"type", "SlidingPointConstraint"}, {"name", "hole"}, {"abscissa", 0.5}},
       {{"type", "SphereModel"}, {"name", "hole marker"}, {"constraint", "hole"}, {"radius", 1e-3}},
       {{"type", "SphereModel"}, {"name", "probe"}, {"radius", 5e-3},
        {"path", {{{"time", 0.0}, {"position", {0, 0, 0}}}, {{"time", 1.0}, {"position", {0.1, 0, 0}}}}}}});
  json scene = test::splineScene(test::planarWave(), more);
  scene["constraint_solver"] = {{"type", "LagrangeMultiplierSolver"}};
  auto loaded = loadScene(scene, "test", test::visualFactory());
  VisualScene visuals(*loaded);
  SceneState s = loaded->state();
  s.time = 0.25;
  visuals.update(s);
  const auto* hole = dynamic_cast<const SphereModel*>(visuals.models()[0]);
  const auto* probe = dynamic_cast<const SphereModel*>(visuals.models()[1]);
  ASSERT_TRUE(hole && probe);
  const auto& spline = *loaded->bodies().front()->curve();
  const Vec3 hole_point = geometry::curvePoint(spline.basis(), spline.block(loaded->state().q), 0.5);
  ASSERT_EQ(hole->centers().rows(), 1);
  EXPECT_LE((hole->centers().row(0).transpose() - hole_point).norm(), 1e-15);
  EXPECT_LE((probe->centers().row(0).transpose() - Vec3(0.025, 0, 0)).norm(), 1e-17);
  EXPECT_EQ(probe->radius(), 5e-3);
}

TEST(SphereModel, NeedsExactlyOnePlacement) {
  try {
    loadScene(test::splineScene(test::planarWave(),
                                json::array({{{"type", "SphereModel"}, {"center", {0, 0, 0}}, {"abscissa", 0.5}}})),
              "scene.json", test::visualFactory());
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("exactly one of"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace filum::visual
