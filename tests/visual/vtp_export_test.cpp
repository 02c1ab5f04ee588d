// ParaView export: the .vtp files of the skinned meshes and their .pvd index, read back
// by an independent parser (tests/support/vtk_xml_reader.hpp), match the meshes exactly.
#include <gtest/gtest.h>

#include <filesystem>

#include "filum/visual/generalized_cylinder_model.hpp"
#include "filum/visual/visual_scene.hpp"
#include "filum/visual/vtp_writer.hpp"
#include "support/vtk_xml_reader.hpp"
#include "visual/visual_test_support.hpp"

namespace filum::visual {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

void expectSameMesh(const test::VtpMesh& read, const TriangleMesh& mesh) {
  ASSERT_EQ(read.number_of_points, mesh.vertexCount());
  ASSERT_EQ(read.number_of_polys, mesh.triangleCount());
  ASSERT_EQ(read.points.size(), 3u * mesh.vertexCount());
  ASSERT_EQ(read.normals.size(), 3u * mesh.vertexCount());
  ASSERT_EQ(read.connectivity.size(), 3u * mesh.triangleCount());
  ASSERT_EQ(read.offsets.size(), static_cast<std::size_t>(mesh.triangleCount()));
  for (int v = 0; v < mesh.vertexCount(); ++v)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(read.points[3 * v + k], mesh.vertices(v, k));  // 17 digits: exact
      EXPECT_EQ(read.normals[3 * v + k], mesh.normals(v, k));
    }
  for (int f = 0; f < mesh.triangleCount(); ++f) {
    EXPECT_EQ(read.offsets[f], 3 * (f + 1));
    for (int k = 0; k < 3; ++k) EXPECT_EQ(read.connectivity[3 * f + k], mesh.triangles(f, k));
  }
}

TEST(VtpExport, SkinnedMeshSeriesIsReadBackExactly) {
  const fs::path dir = fs::path(FILUM_BINARY_DIR) / "test_output" / "visual" / "vtp_series";
  fs::remove_all(dir);
  fs::create_directories(dir / "meshes");
  json more = json::array({{{"type", "GeneralizedCylinder"}, {"name", "skin"}, {"sides", 8}, {"samples", 24}},
                           {{"type", "SphereModel"}, {"name", "end"}, {"abscissa", 1.0}, {"radius", 3e-3}}});
  json scene = test::splineScene(test::helix(), more);
  scene["gravity"] = {0.0, 0.0, -9.81};
  auto loaded = loadScene(scene, "test", test::visualFactory());
  VisualScene visuals(*loaded);
  PvdSeries series((dir / "meshes.pvd").string());
  std::vector<std::vector<TriangleMesh>> written;
  for (int frame = 0; frame < 3; ++frame) {
    for (int k = 0; k < 50 && frame > 0; ++k) ASSERT_TRUE(loaded->step().ok);
    visuals.update(loaded->state());
    std::vector<std::string> files;
    written.emplace_back();
    for (std::size_t i = 0; i < visuals.models().size(); ++i) {
      const std::string file = "meshes/" + visuals.modelName(i) + "_" + std::to_string(frame) + ".vtp";
      writeMeshVtp((dir / file).string(), visuals.models()[i]->mesh());
      files.push_back(file);
      written.back().push_back(visuals.models()[i]->mesh());
    }
    series.addStep(loaded->state().time, files);
  }
  const std::vector<test::PvdEntry> entries = test::readPvd((dir / "meshes.pvd").string());
  ASSERT_EQ(entries.size(), 6u);  // 3 steps × 2 parts
  for (std::size_t e = 0; e < entries.size(); ++e) {
    const int frame = static_cast<int>(e / 2), part = static_cast<int>(e % 2);
    EXPECT_EQ(entries[e].part, part);
    EXPECT_DOUBLE_EQ(entries[e].time, frame * 50 * 1e-4);
    expectSameMesh(test::readVtpMesh((dir / entries[e].file).string()), written[frame][part]);
  }
  // The thread moved under gravity between the frames.
  EXPECT_GT((written[2][0].vertices - written[0][0].vertices).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(VtpExport, RefusesNonFiniteMeshes) {
  TriangleMesh mesh;
  mesh.vertices = Points::Constant(3, 3, std::nan(""));
  mesh.normals = Points::Zero(3, 3);
  mesh.triangles.resize(1, 3);
  mesh.triangles << 0, 1, 2;
  EXPECT_THROW(writeMeshVtp((fs::path(FILUM_BINARY_DIR) / "test_output" / "nan.vtp").string(), mesh), std::runtime_error);
}

}  // namespace
}  // namespace filum::visual
