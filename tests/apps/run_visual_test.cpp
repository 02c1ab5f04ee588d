// `filum run --meshes --render` end to end: the mesh series is a ParaView .pvd whose
// .vtp files parse and match the final OBJ, and the render writes PNG frames, a video and a
// contact sheet. Rendering needs an X display: an Xvfb is started when DISPLAY is unset; the
// render part is skipped only if Xvfb is not installed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "filum/run_command.hpp"
#include "filum/geometry/mesh_file.hpp"
#include "filum/visual/offscreen_renderer.hpp"
#include "support/vtk_xml_reader.hpp"
#include "visual/visual_test_support.hpp"

namespace filum::app {
namespace {

namespace fs = std::filesystem;

TEST(RunVisual, MeshesArePlayableInParaViewAndMatchTheFinalObj) {
  const fs::path out = fs::path(FILUM_BINARY_DIR) / "test_output" / "run_meshes";
  fs::remove_all(out);
  RunOptions options;
  options.scene = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/hanging_thread.json";
  options.out = out.string();
  options.duration = 0.05;
  options.progress = false;
  options.meshes = true;
  std::ostringstream log, progress;
  ASSERT_EQ(runScene(options, log, progress), kRunOk) << log.str();
  const std::vector<test::PvdEntry> entries = test::readPvd((out / "meshes.pvd").string());
  // 6 output frames (t = 0, 0.01, ..., 0.05) × the scene's 2 visual models (skin, held end).
  ASSERT_EQ(entries.size(), 12u);
  for (const test::PvdEntry& e : entries) {
    const test::VtpMesh m = test::readVtpMesh((out / e.file).string());
    EXPECT_EQ(m.points.size(), 3u * m.number_of_points);
    EXPECT_EQ(m.connectivity.size(), 3u * m.number_of_polys);
  }
  // The last skin frame equals the final OBJ's first object (9 significant digits there).
  const test::VtpMesh last = test::readVtpMesh((out / entries[10].file).string());
  EXPECT_EQ(entries[10].part, 0);
  const geometry::PolygonSoup obj =
      geometry::readMeshFile((out / "meshes" / "final_thread_GeneralizedCylinder.ply").string());
  ASSERT_EQ(obj.vertices.rows(), last.number_of_points);
  double worst = 0.0;
  for (int v = 0; v < obj.vertices.rows(); ++v)
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(obj.vertices(v, k) - last.points[3 * v + k]));
  EXPECT_LE(worst, 1e-9);
  EXPECT_TRUE(fs::exists(out / "meshes" / "final.obj"));
}

TEST(RunVisual, RenderWritesFramesVideoAndContactSheet) {
  FILUM_REQUIRE_RENDERING();
  const fs::path out = fs::path(FILUM_BINARY_DIR) / "test_output" / "run_render";
  fs::remove_all(out);
  RunOptions options;
  options.scene = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/hanging_thread.json";
  options.out = out.string();
  options.duration = 0.1;
  options.progress = false;
  options.render = true;
  std::ostringstream log, progress;
  ASSERT_EQ(runScene(options, log, progress), kRunOk) << log.str();
  // Frames at t = 0, 1/30, 2/30, 3/30 s (the camera's default frame interval).
  for (int k = 0; k < 4; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", k);
    EXPECT_TRUE(fs::exists(out / "frames" / name)) << name;
  }
  EXPECT_GT(fs::file_size(out / "video.avi"), 4000u);
  EXPECT_GT(fs::file_size(out / "contact_sheet.png"), 1000u);
  EXPECT_NE(log.str().find("video.avi"), std::string::npos) << log.str();
}

TEST(RunVisual, AFluoroscopyBlockAddsTheCArmsViewAndTheFluoroscopyTime) {
  FILUM_REQUIRE_RENDERING();
  const fs::path out = fs::path(FILUM_BINARY_DIR) / "test_output" / "run_fluoroscopy";
  fs::remove_all(out);
  RunOptions options;
  options.scene = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/guidewire.json";  // the pedal: [0, 1], [1.5, 6] s
  options.out = out.string();
  options.duration = 0.2;
  options.progress = false;
  options.render = true;
  options.png_frames = true;
  std::ostringstream log, progress;
  ASSERT_EQ(runScene(options, log, progress), kRunOk) << log.str();
  // Pulses every 1/15 s (at most as often as the camera's 1/30 s frames): t = 0, 1/15, 2/15, 3/15.
  for (int k = 0; k < 4; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", k);
    EXPECT_TRUE(fs::exists(out / "fluoroscopy" / "frames" / name)) << name;
  }
  EXPECT_FALSE(fs::exists(out / "fluoroscopy" / "frames" / "frame_000004.png"));
  EXPECT_GT(fs::file_size(out / "fluoroscopy" / "contact_sheet.png"), 1000u);
  const nlohmann::json metrics = nlohmann::json::parse(std::ifstream(out / "metrics.json"));
  // The pedal pressed over the whole 0.2 s: the steps' time sum, to round-off.
  EXPECT_NEAR(metrics.at("fluoroscopy_time").get<double>(), 0.2, 1e-12);
  EXPECT_NE(log.str().find("fluoroscopy time"), std::string::npos) << log.str();
}

}  // namespace
}  // namespace filum::app
