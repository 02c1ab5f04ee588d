// The targets of point constraints in the pictures: a grip or a fixed point that no SphereModel
// marks gets a green sphere at its target (hidden once it lets go); one a SphereModel names is
// drawn once.
#include <gtest/gtest.h>

#include "filum/visual/sphere_model.hpp"
#include "filum/visual/visual_scene.hpp"
#include "visual/visual_test_support.hpp"

namespace filum::visual {
namespace {

using nlohmann::json;

int markersOf(const VisualScene& visuals, const Constraint* c) {
  int count = 0;
  for (const VisualModel* model : visuals.models())
    if (const auto* spheres = dynamic_cast<const SphereModel*>(model)) count += spheres->markedConstraint() == c;
  return count;
}

TEST(TargetMarker, AnUnmarkedGripGetsASphereAtItsTargetUntilItLetsGo) {
  const json more = json::array({{{"type", "FixedPointConstraint"}, {"name", "grip"}, {"abscissa", 1.0},
                                  {"target", {0.1, 0.0, 0.01}}, {"release_at", 0.001}}});
  auto scene = loadScene(test::splineScene(test::planarWave(), more), "markers", test::visualFactory());
  VisualScene visuals(*scene);
  visuals.update(scene->state());
  const Constraint* grip = scene->constraints().front();
  ASSERT_EQ(markersOf(visuals, grip), 1);
  const SphereModel* marker = nullptr;
  for (const VisualModel* model : visuals.models())
    if (const auto* spheres = dynamic_cast<const SphereModel*>(model); spheres && spheres->markedConstraint() == grip)
      marker = spheres;
  ASSERT_EQ(marker->centers().rows(), 1);
  EXPECT_EQ(Vec3(marker->centers().row(0)), Vec3(0.1, 0.0, 0.01));  // the target itself, copied
  while (scene->state().time < 0.002) ASSERT_TRUE(scene->step().ok);
  visuals.update(scene->state());
  EXPECT_EQ(marker->centers().rows(), 0);  // released: nothing left to mark
}

TEST(TargetMarker, AGripASceneMarksIsDrawnOnce) {
  const json more = json::array({{{"type", "FixedPointConstraint"}, {"name", "grip"}, {"abscissa", 0.0}},
                                 {{"type", "SphereModel"}, {"constraint", "grip"}, {"radius", 0.002}}});
  auto scene = loadScene(test::splineScene(test::planarWave(), more), "markers", test::visualFactory());
  VisualScene visuals(*scene);
  EXPECT_EQ(markersOf(visuals, scene->constraints().front()), 1);
}

}  // namespace
}  // namespace filum::visual
