// Headless rendering: a rendered frame of a known scene is not blank — the projected
// axis of the thread falls on thread-coloured pixels, and pixels away from the thread show the
// background — with no golden image: the expected pixels come from the pinhole model of
// camera.hpp. The test starts its own Xvfb when DISPLAY is unset and skips only if Xvfb is not
// installed. Also: the frame recorder writes PNG frames, a Motion-JPEG AVI and a contact sheet.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "filum/core/scene_error.hpp"
#include "filum/visual/camera.hpp"
#include "filum/visual/frame_recorder.hpp"
#include "filum/visual/generalized_cylinder_model.hpp"
#include "filum/visual/heads_up_display.hpp"
#include "filum/visual/image_file.hpp"
#include "filum/visual/offscreen_renderer.hpp"
#include "filum/visual/visual_scene.hpp"
#include "visual/visual_test_support.hpp"

namespace filum::visual {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const Vec3 kThreadColor(0.95, 0.45, 0.05);  // orange
const json kCamera = {{"position", {0.05, -0.25, 0.06}}, {"look_at", {0.05, 0.0, 0.0}}, {"up", {0, 0, 1}},
                      {"fov", 30}, {"size", {640, 400}}, {"background", {1, 1, 1}}};

TEST(OffscreenRenderer, TheThreadsProjectedAxisIsOnThreadPixelsAndTheRestIsBackground) {
  FILUM_REQUIRE_RENDERING();
  // A wave in the xz-plane (so that a mirrored or shifted picture would miss it by tens of
  // pixels), 2 mm radius, seen from the front and a little above.
  json wave = json::array();
  for (int i = 0; i < 16; ++i) {
    const double x = 0.1 * i / 15;
    wave.push_back({x, 0.0, 0.012 * std::sin(2.0 * 3.141592653589793 * x / 0.06)});
  }
  const json more = json::array({{{"type", "GeneralizedCylinder"}, {"color", {kThreadColor.x(), kThreadColor.y(), kThreadColor.z()}},
                                  {"sides", 16}, {"samples", 120}}});
  const json document = test::splineScene(wave, more, 2e-3, kCamera);
  auto scene = loadScene(document, "render test", test::visualFactory());
  VisualScene visuals(*scene);
  visuals.update(scene->state());
  const CameraSettings camera = *readCamera(document, "render test");
  OffscreenRenderer renderer(camera);
  const Image image = renderer.render(visuals.models());
  ASSERT_EQ(image.width, 640);
  ASSERT_EQ(image.height, 400);
  const fs::path dir = fs::path(FILUM_BINARY_DIR) / "test_output" / "visual";
  fs::create_directories(dir);
  writePng((dir / "render_test.png").string(), image);  // for a look by eye

  const auto* skin = dynamic_cast<const GeneralizedCylinderModel*>(visuals.models().front());
  ASSERT_NE(skin, nullptr);
  // Thread pixels: at the projection of every axis sample, an orange pixel (red well above
  // blue, not white). Shading changes the brightness, not the hue.
  std::vector<Pixel> axis;
  int on_thread = 0;
  for (Eigen::Index k = 0; k < skin->axis().rows(); ++k) {
    const Pixel p = project(camera, skin->axis().row(k).transpose());
    axis.push_back(p);
    const auto [b, g, r] = image.at(static_cast<int>(p.u), static_cast<int>(p.v));
    const bool orange = r > 120 && r > g + 30 && g > b && r - b > 90;
    on_thread += orange;
    EXPECT_TRUE(orange) << "axis sample " << k << " at pixel (" << p.u << ", " << p.v << ") is (b, g, r) = ("
                        << int(b) << ", " << int(g) << ", " << int(r) << ")";
  }
  EXPECT_EQ(on_thread, static_cast<int>(axis.size()));
  // Background: every pixel farther than the projected radius + 3 pixels from every projected
  // axis point (and outside the caps) is exactly the background colour.
  int background = 0, wrong = 0;
  for (int y = 0; y < image.height; y += 2)
    for (int x = 0; x < image.width; x += 2) {
      double nearest = 1e9, radius_pixels = 0.0;
      for (const Pixel& p : axis) {
        const double d = std::hypot(p.u - x, p.v - y);
        if (d < nearest) {
          nearest = d;
          radius_pixels = camera.focalPixels() * 2e-3 / p.depth;
        }
      }
      if (nearest <= radius_pixels + 3.0) continue;
      const auto [b, g, r] = image.at(x, y);
      ++background;
      if (b != 255 || g != 255 || r != 255) ++wrong;
    }
  EXPECT_GT(background, 50000);
  EXPECT_EQ(wrong, 0) << "non-background pixels away from the thread";
  // And the thread covers a sensible area: between the axis length × diameter bounds.
  int coloured = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const auto [b, g, r] = image.at(x, y);
      coloured += (b != 255 || g != 255 || r != 255);
    }
  EXPECT_GT(coloured, 1500);
  EXPECT_LT(coloured, 40000);
}

TEST(OffscreenRenderer, CameraFromTheSceneIsCheckedWithFileAndPath) {
  json document = test::splineScene(test::planarWave(), json::array(), 2e-3, kCamera);
  document["camera"]["fov"] = 200;
  try {
    readCamera(document, "scene.json");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.json: /camera/fov"), std::string::npos) << e.what();
  }
  document["camera"].erase("fov");
  document["camera"]["zoom"] = 2;
  EXPECT_THROW(readCamera(document, "scene.json"), SceneError);  // unknown key
}

TEST(FrameRecorder, WritesPngFramesAMotionJpegVideoAndAContactSheet) {
  FILUM_REQUIRE_RENDERING();
  const fs::path dir = fs::path(FILUM_BINARY_DIR) / "test_output" / "visual" / "recorder";
  fs::remove_all(dir);
  json document = test::splineScene(test::helix(), json::array(), 2e-3, kCamera);
  document["gravity"] = {0.0, 0.0, -9.81};
  auto scene = loadScene(document, "recorder test", test::visualFactory());
  VisualScene visuals(*scene);
  OffscreenRenderer renderer(*readCamera(document, "recorder test"));
  FrameRecorderOptions options;
  options.directory = dir.string();
  options.fps = 25.0;
  options.expected_frames = 20;
  options.sheet_frames = 6;
  options.sheet_columns = 3;
  options.title = "recorder test";
  FrameRecorder recorder(options);
  for (int frame = 0; frame < 7; ++frame) {  // stops early: 7 of the 20 expected frames
    for (int k = 0; k < 100 && frame > 0; ++k) ASSERT_TRUE(scene->step().ok);
    visuals.update(scene->state());
    Image image = renderer.render(visuals.models());
    drawHeadsUp(image, headsUpText(scene->state().time, 0.25, scene->energy(scene->state()).total()));
    recorder.add(image, scene->state().time);
  }
  recorder.finish();
  EXPECT_EQ(recorder.frames(), 7);
  for (int frame = 0; frame < 7; ++frame) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", frame);
    EXPECT_EQ(readPng((dir / "frames" / name).string()).width, 640);
  }
  // A RIFF/AVI file with Motion-JPEG frames.
  std::ifstream video(recorder.videoPath(), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(video)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 7u * 1000u);
  EXPECT_EQ(bytes.substr(0, 4), "RIFF");
  EXPECT_EQ(bytes.substr(8, 4), "AVI ");
  EXPECT_NE(bytes.find("MJPG"), std::string::npos);
  // The contact sheet: picks 0 and 4 of the planned 6 (0, 4, 8, ...), then the last frame (6).
  const Image sheet = readPng(recorder.sheetPath());
  EXPECT_EQ(sheet.width, 6 + 3 * (400 + 6));
  EXPECT_EQ(sheet.height, 34 + 6 + 1 * (250 + 6));
}

TEST(ContactSheet, PicksSpreadFramesAndKeepTheEnds) {
  EXPECT_EQ(contactSheetPicks(61, 12), (std::vector<int>{0, 5, 11, 16, 22, 27, 33, 38, 44, 49, 55, 60}));
  EXPECT_EQ(contactSheetPicks(5, 12), (std::vector<int>{0, 1, 2, 3, 4}));
}

}  // namespace
}  // namespace filum::visual
