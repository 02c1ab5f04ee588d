// BodyPoint (core/body_point.hpp): the one form of a point on a curve body. Its map is the
// body's P(s) (CurveBody::position), a force at it maps up as Σ b_j F (the work F·Ṗ(s) equals
// the generalized force · q̇), and after a body refines its points the row is evaluated again in
// the new layout on first use, with no call from the holder: the same material point, where it
// was (knot insertion keeps the curve), on the refined body and on a body after it whose points
// were renumbered.
// Tolerances: sums of ≤ 4 products of O(0.1) numbers, 1e-15 m; the refined curve equals the old
// to round-off of the Oslo matrix (~1e-16 relative), 1e-15 m asserted.
#include <gtest/gtest.h>

#include "filum/core/body_point.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"
#include "support/library_components.hpp"

namespace filum {
namespace {

std::unique_ptr<Scene> thread() {
  nlohmann::json document = readJsonFile(std::string(FILUM_TEST_DATA_DIR) + "/minimal_thread.json");
  auto scene = loadScene(document, "in-memory", test::libraryComponents());
  scene->init();
  for (int k = 0; k < 50; ++k) EXPECT_TRUE(scene->step().ok);  // a bent, moving thread
  return scene;
}

TEST(BodyPoint, MapsLikeTheCurveAndMapsForcesUpByItsRow) {
  auto scene = thread();
  const CurveBody& body = *scene->bodies().front()->curve();
  const BodyPoint point(body, 0.37);
  const SceneState& s = scene->state();
  EXPECT_LE((point.map(s.q) - body.position(s.q, 0.37)).norm(), 1e-15);
  EXPECT_LE((point.mapTangent(s.q) - body.tangent(s.q, 0.37)).norm(), 1e-15);
  // Virtual work: (Σ_j b_j F)·q̇ = F·Ṗ(s).
  VecX B = VecX::Zero(s.v.size());
  const Vec3 F(0.3, -1.1, 0.4);
  point.addForce(F, B);
  EXPECT_NEAR(B.dot(s.v), F.dot(point.map(s.v)), 1e-15 * (1.0 + std::abs(F.dot(point.map(s.v)))));
}

TEST(BodyPoint, FollowsARefinementOfItsBodyOrOfABodyBefore) {
  nlohmann::json document = readJsonFile(std::string(FILUM_TEST_DATA_DIR) + "/minimal_thread.json");
  nlohmann::json second = document["nodes"][0];
  second["name"] = "second thread";
  second["components"][0]["control_points"]["from"] = {0, 0.02, 0};
  second["components"][0]["control_points"]["to"] = {0.1, 0.02, 0};
  document["nodes"].push_back(second);
  auto scene = loadScene(document, "in-memory", test::libraryComponents());
  scene->init();
  for (int k = 0; k < 50; ++k) ASSERT_TRUE(scene->step().ok);
  CurveBody& first_body = *scene->bodies()[0]->curve();
  const CurveBody& second_body = *scene->bodies()[1]->curve();
  const BodyPoint on_first(first_body, 0.62), on_second(second_body, 0.4);
  const Vec3 first_before = on_first.map(scene->state().q), second_before = on_second.map(scene->state().q);
  const int row_before = on_first.row().first, global_before = on_second.firstPoint();
  scene->refine(first_body, {0.1, 0.2, 0.3});  // three points inserted before s = 0.62
  EXPECT_EQ(on_first.row().first, row_before + 3);      // its own row, evaluated again
  EXPECT_EQ(on_second.firstPoint(), global_before + 3);  // renumbered after the first body
  EXPECT_LE((on_first.map(scene->state().q) - first_before).norm(), 1e-15);
  EXPECT_LE((on_second.map(scene->state().q) - second_before).norm(), 0.0);  // carried over as is
}

}  // namespace
}  // namespace filum
