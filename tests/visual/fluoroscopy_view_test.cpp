// The fluoroscopy view (visual/fluoroscopy_view.hpp): the C-arm's geometry against the central
// projection written out here from the definitions of LAO/RAO and cranial/caudal angles (an AP
// view shows the patient's left on the right, magnified SID/SOD at the isocentre), the scene
// block's refusals, and a rendered X-ray frame whose tones follow I = I₀ Π (1 − a_k): a wire and a
// steel sphere dark where they project, the table unseen, the background white under the
// vignette, black outside the round field, and the same noise for the same frame number.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "filum/core/scene_error.hpp"
#include "filum/visual/fluoroscopy_view.hpp"
#include "filum/visual/offscreen_renderer.hpp"
#include "filum/visual/visual_scene.hpp"
#include "visual/visual_test_support.hpp"

namespace filum::visual {
namespace {

using nlohmann::json;

FluoroscopyView view(const json& block) {
  return FluoroscopyView::fromParams(Params(block, "fluoro.json", "/fluoroscopy"));
}

// The projections below are a few products and quotients of O(1) numbers: round-off of ~1e-13
// of the 720-pixel image.
constexpr double kPixelRoundOff = 1e-9;

TEST(FluoroscopyView, AnAPViewShowsThePatientsLeftOnTheRightMagnifiedBySidOverSod) {
  const FluoroscopyView v = view({{"source_isocenter", 0.7}, {"source_detector", 1.0}, {"field", 0.25}, {"size", 720}});
  const Vec3 iso(0.01, 0.02, 0.03);
  const double delta = 0.02, pixels_per_metre = 720.0 * 1.0 / (0.25 * 0.7);  // size · (SID/SOD) / field
  const Pixel centre = v.project(iso, iso);
  EXPECT_NEAR(centre.u, 360.0, kPixelRoundOff);
  EXPECT_NEAR(centre.v, 360.0, kPixelRoundOff);
  const Pixel left = v.project(iso, iso + delta * Vec3::UnitX());  // LPS: x is the patient's left
  EXPECT_NEAR(left.u - 360.0, delta * pixels_per_metre, kPixelRoundOff);
  EXPECT_NEAR(left.v, 360.0, kPixelRoundOff);
  const Pixel head = v.project(iso, iso + delta * Vec3::UnitZ());
  EXPECT_NEAR(head.v - 360.0, -delta * pixels_per_metre, kPixelRoundOff);
}

TEST(FluoroscopyView, ObliqueAndAngulatedViewsFollowTheCArmsDefinition) {
  const double sod = 0.75, sid = 1.05, field = 0.3, size = 720, delta = 0.03;
  const double f = size * sid / field;  // focal length in pixels: (size/2) / tan(fov/2), tan(fov/2) = field/2/SID
  const Vec3 iso = Vec3::Zero();
  const Vec3 anterior(0, -1, 0), superior(0, 0, 1);
  for (const double lao : {30.0, -40.0}) {
    // d = cos α A + sin α L; the image's right e_r = S × d = cos α L − sin α A: an anterior point
    // δA moves by −δ sin α to the right, at depth SOD + δ cos α.
    const double a = lao * M_PI / 180.0;
    const Pixel p = view({{"lao", lao}}).project(iso, iso + delta * anterior);
    EXPECT_NEAR(p.u - size / 2, -f * delta * std::sin(a) / (sod + delta * std::cos(a)), kPixelRoundOff) << lao;
    EXPECT_NEAR(p.v, size / 2, kPixelRoundOff) << lao;
  }
  for (const double cranial : {20.0, -25.0}) {
    // d = cos β A + sin β S; up = (S − sin β d)/cos β: a superior point δS rises by δ cos β at
    // depth SOD + δ sin β.
    const double b = cranial * M_PI / 180.0;
    const Pixel p = view({{"cranial", cranial}}).project(iso, iso + delta * superior);
    EXPECT_NEAR(p.v - size / 2, -f * delta * std::cos(b) / (sod + delta * std::sin(b)), kPixelRoundOff) << cranial;
    EXPECT_NEAR(p.u, size / 2, kPixelRoundOff) << cranial;
  }
  // The patient's axes given in the scene: left −y, posterior +x, so superior = left × posterior = +z.
  const FluoroscopyView turned = view({{"left", {0, -1, 0}}, {"posterior", {1, 0, 0}}});
  EXPECT_NEAR((turned.superior() - Vec3::UnitZ()).norm(), 0.0, 1e-15);
  EXPECT_GT(turned.project(iso, Vec3(0, -delta, 0)).u, size / 2 + 1);  // the patient's left on the right
}

TEST(FluoroscopyView, TheBlockRefusesWhatNoCArmDoesAndNamesThePlace) {
  const auto refused = [](const json& block, const std::string& expected) {
    try {
      view(block);
      ADD_FAILURE() << "accepted " << block.dump();
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  refused({{"lao", 200}}, "/fluoroscopy/lao");
  refused({{"cranial", -75}}, "/fluoroscopy/cranial");
  refused({{"source_isocenter", 1.2}, {"source_detector", 1.0}}, "/fluoroscopy/source_detector");
  refused({{"left", {1, 0, 0}}, {"posterior", {1, 1, 0}}}, "/fluoroscopy/posterior");
  refused({{"zoom", 2}}, "zoom");
}

TEST(FluoroscopyView, EachKindHasItsXRayOpacityAndASceneMaySetIt) {
  json points = json::array();
  for (int i = 0; i < 8; ++i) points.push_back({0.1 * i / 7, 0.0, 0.0});
  json document = test::splineScene(points, json::array(), 2e-3);
  document["nodes"].push_back(
      {{"name", "ball"},
       {"components", {{{"type", "SphereObstacle"}, {"center", {0.05, 0.0, 0.03}}, {"radius", 0.005}},
                       {{"type", "ObstacleModel"}, {"xray_opacity", 0.5}}}}});  // alone: the kind's colours kept
  document["nodes"].push_back(
      {{"name", "table"}, {"components", {{{"type", "PlaneObstacle"}, {"point", {0, 0.02, 0}}, {"normal", {0, -1, 0}}}}}});
  auto scene = loadScene(document, "fluoro", test::visualFactory());
  VisualScene visuals(*scene);
  std::vector<double> opacities;
  for (const VisualModel* m : visuals.models()) opacities.push_back(m->xrayOpacity());
  std::sort(opacities.begin(), opacities.end());
  // The table (0), the ball as the scene says (0.5), the thread's default skin (0.85).
  EXPECT_EQ(opacities, (std::vector<double>{0.0, 0.5, 0.85}));
  for (const VisualModel* m : visuals.models())
    if (m->xrayOpacity() == 0.5) {
      EXPECT_EQ(m->material().color, Vec3(0.70, 0.70, 0.75));  // a sphere's default colour
    }
}

TEST(FluoroscopyView, AFrameIsDarkWhereTheWireAndTheSteelProjectAndWhiteElsewhere) {
  FILUM_REQUIRE_RENDERING();
  // A wire (r = 2 mm) along the patient's left–right axis, a steel ball above it on the left, the
  // table under the patient's back (posterior, +y), crossed by every ray; seen AP without noise.
  json points = json::array();
  for (int i = 0; i < 8; ++i) points.push_back({0.1 * i / 7, 0.0, 0.0});
  json document = test::splineScene(points, json::array(), 2e-3);
  document["nodes"].push_back(
      {{"name", "things"},
       {"components", {{{"type", "SphereObstacle"}, {"center", {0.08, 0.0, 0.03}}, {"radius", 0.005}},
                       {{"type", "PlaneObstacle"}, {"point", {0, 0.02, 0}}, {"normal", {0, -1, 0}}}}}});
  auto scene = loadScene(document, "fluoro", test::visualFactory());
  VisualScene visuals(*scene);
  visuals.update(scene->state());
  const FluoroscopyView v = view({{"noise", 0.0}, {"size", 480}, {"field", 0.2}});
  const Vec3 iso(0.05, 0.0, 0.01);
  OffscreenRenderer renderer(v.camera(iso));
  const Image rendered = renderer.render(visuals.models(), OffscreenRenderer::Style::kXray);
  const Image frame = v.finish(rendered, 0);
  const auto grey = [&](const Vec3& x) {
    const Pixel p = v.project(iso, x);
    return static_cast<int>(frame.at(static_cast<int>(p.u), static_cast<int>(p.v))[0]);
  };
  // Wire: two layers of a = 0.85 transmit 2.25 % (6 of 255); steel, two of 0.95: 0.25 %. Asked
  // below a tenth of full scale: an antialiased edge or one layer more is still far from white.
  // (A uniform cubic B-spline's curve spans the middle of its control polygon: x in [0.014, 0.086].)
  for (const double x : {0.03, 0.05, 0.07}) EXPECT_LT(grey(Vec3(x, 0.0, 0.0)), 26) << "wire at x = " << x;
  EXPECT_LT(grey(Vec3(0.08, 0.0, 0.03)), 26) << "steel ball";
  // The mirror agrees with the projection: where the ball would be if the picture were mirrored
  // once more (the patient's right), nothing is.
  const Pixel ball = v.project(iso, Vec3(0.08, 0.0, 0.03));
  EXPECT_GT(static_cast<int>(frame.at(static_cast<int>(480 - ball.u), static_cast<int>(ball.v))[0]), 200);
  // Background: white times the vignette 1 − 0.3 r² (r from the field's centre, 1 at its rim),
  // to the rounding of one grey level; the table (X-ray opacity 0) is not seen.
  for (const Vec3& x : {Vec3(0.05, 0.0, -0.03), Vec3(0.02, 0.0, 0.05), Vec3(0.08, 0.0, -0.04)}) {
    const Pixel p = v.project(iso, x);
    const double radius = std::hypot(static_cast<int>(p.u) + 0.5 - 240.0, static_cast<int>(p.v) + 0.5 - 240.0) / 240.0;
    ASSERT_LT(radius, 1.0);
    EXPECT_NEAR(grey(x), 255.0 * (1.0 - 0.3 * radius * radius), 1.0) << x.transpose();
  }
  EXPECT_EQ(frame.at(2, 2)[0], 0) << "outside the round field";
  // Noise: the same for the same frame number, other for another.
  const FluoroscopyView noisy = view({{"noise", 0.02}, {"size", 480}, {"field", 0.2}});
  EXPECT_EQ(noisy.finish(rendered, 7).bgr, noisy.finish(rendered, 7).bgr);
  EXPECT_NE(noisy.finish(rendered, 7).bgr, noisy.finish(rendered, 8).bgr);
}

}  // namespace
}  // namespace filum::visual
