// Obstacles in the pictures: every obstacle is drawn as what it is (ObstacleModel), by default in
// its kind's colours or as a scene's ObstacleModel names it — a capsule's and a sphere's vertices
// lie on their surfaces, a plane's patch lies in the plane under the bodies, a mesh is the
// obstacle's own, a moving probe is drawn where it is — and a rendered frame shows the table's
// colour where the table is (the pinhole projection of camera.hpp, no golden image).
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "filum/collision/obstacle.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/visual/camera.hpp"
#include "filum/visual/obstacle_model.hpp"
#include "filum/visual/offscreen_renderer.hpp"
#include "filum/visual/visual_scene.hpp"
#include "visual/visual_test_support.hpp"

namespace filum::visual {
namespace {

using nlohmann::json;

/// The splineScene of the visual tests (a straight thread from x = 0 to 0.1 m) with a second
/// node holding `obstacles`.
json sceneWithObstacles(const json& obstacles, const json& camera = nullptr) {
  json points = json::array();
  for (int i = 0; i < 8; ++i) points.push_back({0.1 * i / 7, 0.0, 0.0});
  json document = test::splineScene(points, json::array(), 2e-3, camera);
  document["nodes"].push_back({{"name", "obstacles"}, {"components", obstacles}});
  return document;
}

const ObstacleModel* drawingOf(const VisualScene& visuals, const std::string& name) {
  for (const VisualModel* model : visuals.models())
    if (const auto* drawing = dynamic_cast<const ObstacleModel*>(model))
      if (drawing->obstacle()->name() == name) return drawing;
  return nullptr;
}

// Vertices are written from doubles computed by a few products and sums of O(1) numbers scaled
// by the size: round-off of a few ulps of the size.
constexpr double kRoundOff = 1e-14;

TEST(ObstacleModel, EveryObstacleIsDrawnOnItsSurfaceInItsKindsColours) {
  const json obstacles = json::array(
      {{{"type", "PlaneObstacle"}, {"name", "table"}, {"point", {0, 0, -0.02}}, {"normal", {0, 0, 1}}},
       {{"type", "CapsuleObstacle"}, {"name", "peg"}, {"a", {0.02, -0.01, 0.01}}, {"b", {0.03, 0.02, 0.015}}, {"radius", 0.003}},
       {{"type", "SphereObstacle"}, {"name", "ball"}, {"center", {0.07, 0.0, 0.01}}, {"radius", 0.004}}});
  auto scene = loadScene(sceneWithObstacles(obstacles), "obstacles", test::visualFactory());
  VisualScene visuals(*scene);
  visuals.update(scene->state());

  const ObstacleModel* table = drawingOf(visuals, "table");
  ASSERT_NE(table, nullptr);
  EXPECT_FALSE(table->framed());  // a camera frames the bodies, not the patch sized after them
  const TriangleMesh& patch = table->mesh();
  ASSERT_EQ(patch.triangleCount(), 2);
  Vec3 lower = patch.vertices.colwise().minCoeff(), upper = patch.vertices.colwise().maxCoeff();
  EXPECT_NEAR(lower.z(), -0.02, kRoundOff);
  EXPECT_NEAR(upper.z(), -0.02, kRoundOff);
  // Under the whole thread (x from 0 to 0.1, y = 0).
  EXPECT_LT(lower.x(), 0.0);
  EXPECT_GT(upper.x(), 0.1);
  EXPECT_LT(lower.y(), 0.0);
  EXPECT_GT(upper.y(), 0.0);
  // Seen from above: the triangles' right-hand normal is the plane's.
  const Vec3 e1 = patch.vertices.row(patch.triangles(0, 1)) - patch.vertices.row(patch.triangles(0, 0));
  const Vec3 e2 = patch.vertices.row(patch.triangles(0, 2)) - patch.vertices.row(patch.triangles(0, 0));
  EXPECT_GT(e1.cross(e2).z(), 0.0);
  EXPECT_EQ(table->material().color,
            ObstacleModel::defaultMaterial(collision::ObstacleShape::plane(Vec3::Zero(), Vec3::UnitZ())).color);

  const ObstacleModel* peg = drawingOf(visuals, "peg");
  ASSERT_NE(peg, nullptr);
  const Vec3 a(0.02, -0.01, 0.01), b(0.03, 0.02, 0.015);
  for (int i = 0; i < peg->mesh().vertexCount(); ++i) {
    const Vec3 x = peg->mesh().vertices.row(i);
    const double t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    EXPECT_NEAR((x - (a + t * (b - a))).norm(), 0.003, kRoundOff) << "vertex " << i;
  }
  const ObstacleModel* ball = drawingOf(visuals, "ball");
  ASSERT_NE(ball, nullptr);
  for (int i = 0; i < ball->mesh().vertexCount(); ++i)
    EXPECT_NEAR((ball->mesh().vertices.row(i).transpose() - Vec3(0.07, 0.0, 0.01)).norm(), 0.004, kRoundOff);
  // The camera's box: the thread, the peg and the ball, not the table's patch.
  Vec3 box_lower, box_upper;
  ASSERT_TRUE(visuals.bounds(box_lower, box_upper));
  EXPECT_GT(box_lower.z(), -0.02 + 1e-3);
}

TEST(ObstacleModel, ASceneNamesTheColourAndTheObstacleIsDrawnOnce) {
  json obstacles = json::array(
      {{{"type", "SphereObstacle"}, {"name", "ball"}, {"center", {0.07, 0.0, 0.01}}, {"radius", 0.004}},
       {{"type", "ObstacleModel"}, {"name", "ball drawing"}, {"obstacle", "ball"}, {"color", {0.9, 0.1, 0.1}}}});
  auto scene = loadScene(sceneWithObstacles(obstacles), "obstacles", test::visualFactory());
  VisualScene visuals(*scene);
  int drawings = 0;
  for (const VisualModel* model : visuals.models()) drawings += dynamic_cast<const ObstacleModel*>(model) != nullptr;
  EXPECT_EQ(drawings, 1);
  EXPECT_EQ(drawingOf(visuals, "ball")->material().color, Vec3(0.9, 0.1, 0.1));

  // A name that is not there is refused, naming the place and the node's obstacles.
  obstacles[1]["obstacle"] = "bal";
  auto bad = loadScene(sceneWithObstacles(obstacles), "obstacles.json", test::visualFactory());
  try {
    VisualScene refused(*bad);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/obstacle"), std::string::npos) << what;
    EXPECT_NE(what.find("\"ball\""), std::string::npos) << what;
  }
}

TEST(ObstacleModel, AProbeIsDrawnWhereItIs) {
  const json obstacles = json::array({{{"type", "ProbeSphere"}, {"name", "probe"}, {"radius", 0.005},
                                       {"path", {{{"time", 0.0}, {"position", {0.05, 0.0, 0.05}}},
                                                 {{"time", 0.01}, {"position", {0.05, 0.0, 0.03}}}}}}});
  auto scene = loadScene(sceneWithObstacles(obstacles), "probe", test::visualFactory());
  VisualScene visuals(*scene);
  for (int k = 0; k < 100; ++k) scene->step();  // t = 0.01 s: the probe's last key
  visuals.update(scene->state());
  const ObstacleModel* probe = drawingOf(visuals, "probe");
  ASSERT_NE(probe, nullptr);
  const Vec3 centre = probe->mesh().vertices.colwise().mean();
  // Drawn on its path at the state's time (not where the last step's contacts saw it, one step
  // of 2 m/s × 0.1 ms = 0.2 mm earlier); the UV sphere's vertices are symmetric about its centre
  // to round-off (a mean of a few hundred coordinates of 0.05 m: far below 1e-14 m).
  EXPECT_NEAR((centre - Vec3(0.05, 0.0, 0.03)).norm(), 0.0, 1e-14);
}

TEST(ObstacleModel, ARenderedFrameShowsTheTablesColourWhereTheTableIs) {
  FILUM_REQUIRE_RENDERING();
  const json camera = {{"position", {0.05, -0.25, 0.06}}, {"look_at", {0.05, 0.0, 0.0}}, {"up", {0, 0, 1}},
                       {"fov", 30}, {"size", {640, 400}}, {"background", {1, 1, 1}}};
  const json obstacles =
      json::array({{{"type", "PlaneObstacle"}, {"name", "table"}, {"point", {0, 0, -0.03}}, {"normal", {0, 0, 1}}}});
  const json document = sceneWithObstacles(obstacles, camera);
  auto scene = loadScene(document, "render", test::visualFactory());
  VisualScene visuals(*scene);
  visuals.update(scene->state());
  const CameraSettings settings = *readCamera(document, "render");
  OffscreenRenderer renderer(settings);
  const Image image = renderer.render(visuals.models());
  // On the table, in front of the thread: lit table colour (0.80, 0.78, 0.72), r >= g >= b up
  // to a level of quantization, neither background white nor dark; above the horizon nothing.
  for (const Vec3& x : {Vec3(0.02, -0.03, -0.03), Vec3(0.05, -0.06, -0.03), Vec3(0.09, -0.02, -0.03)}) {
    const Pixel p = project(settings, x);
    const auto [blue, green, red] = image.at(static_cast<int>(p.u), static_cast<int>(p.v));
    EXPECT_FALSE(blue == 255 && green == 255 && red == 255) << "background at the table point " << x.transpose();
    EXPECT_GE(red + 2, green) << x.transpose();
    EXPECT_GE(green + 2, blue) << x.transpose();
    EXPECT_GT(red, 40) << x.transpose();
  }
  const Pixel sky = project(settings, Vec3(0.05, 0.0, 0.04));
  const auto [blue, green, red] = image.at(static_cast<int>(sky.u), static_cast<int>(sky.v));
  EXPECT_TRUE(blue == 255 && green == 255 && red == 255);
}

}  // namespace
}  // namespace filum::visual
