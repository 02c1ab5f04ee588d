// BodyPoint (core/body_point.hpp): the one form of a point on a curve body and the mapping through
// which every force at a point of a curve goes up. Its map is the body's P(s)
// (CurveBody::position), a force at it maps up as Σ b_j F (the work F·Ṗ(s) equals the generalized
// force · q̇), both kinds of point (of the curve, of a chord between two points of it) pass the
// generic mapping test, and after a body refines its points the row is evaluated again in the
// new layout on first use, with no call from the holder: the same material point, where it was
// (knot insertion keeps the curve), on the refined body and on a body after it whose points were
// renumbered.
// Tolerances: sums of ≤ 8 products of O(0.1) numbers, 1e-15 m; the refined curve equals the old
// to round-off of the Oslo matrix (~1e-16 relative), 1e-15 m asserted.
#include <gtest/gtest.h>

#include "filum/core/body_point.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"
#include "support/finite_difference.hpp"
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

// The generic mapping test (tests/support/finite_difference.hpp) on each kind of point. The
// mapping is linear, so the central differences carry round-off only, ε |x| / h ≈ 2e-16 · 0.1 m /
// 1e-6 m = 2e-11 relative to 1 + |J v| ~ 1: 1e-10 asserted.
TEST(BodyPoint, EveryKindOfPointPassesTheGenericMappingTest) {
  auto scene = thread();
  CurveBody& body = *scene->bodies().front()->curve();
  const ConstPointsMap q = body.block(scene->state().q);
  for (const double s : {0.0, 0.37, 0.5, 1.0}) {
    SCOPED_TRACE("the curve point s = " + std::to_string(s));
    test::expectMappingConsistent(BodyPoint(body, s), q, 1e-6, 1e-10);
  }
  BasisRow row0, row1;
  body.row(0.3, row0);
  body.row(0.34, row1);
  BodyPoint chord;
  chord.attachChord(body, 0.3, row0, 0.34, row1, 0.4);
  ASSERT_TRUE(chord.onChord());
  EXPECT_DOUBLE_EQ(chord.abscissa(), 0.6 * 0.3 + 0.4 * 0.34);
  {
    SCOPED_TRACE("a chord point");
    test::expectMappingConsistent(chord, q, 1e-6, 1e-10);
  }
  // The chord point is (1 − t) P(s₀) + t P(s₁), and its weights sum to one (a rigid translation
  // moves it rigidly).
  const VecX& x = scene->state().q;
  EXPECT_LE((chord.map(x) - (0.6 * body.position(x, 0.3) + 0.4 * body.position(x, 0.34))).norm(), 1e-15);
  double sum = 0.0;
  for (int j = 0; j < chord.weights().count; ++j) sum += chord.weights().weight[j];
  EXPECT_NEAR(sum, 1.0, 1e-15);
  // After a refinement both kinds are evaluated again: the same points, on the new layout.
  const Vec3 chord_before = chord.map(x), curve_before = BodyPoint(body, 0.37).map(x);
  const BodyPoint curve_point(body, 0.37);
  scene->refine(body, {0.2, 0.32, 0.6});
  const VecX& refined = scene->state().q;
  EXPECT_LE((chord.map(refined) - chord_before).norm(), 1e-15);
  EXPECT_LE((curve_point.map(refined) - curve_before).norm(), 1e-15);
  SCOPED_TRACE("after a refinement");
  const ConstPointsMap q_refined = body.block(refined);
  test::expectMappingConsistent(chord, q_refined, 1e-6, 1e-10);
  test::expectMappingConsistent(curve_point, q_refined, 1e-6, 1e-10);
}

// A point at a strand's end at a cut (a sphere sample's row there is the left limit,
// evaluateOnStrand) stays that strand's end point when the layout changes again: its weights on
// the first strand's points only, its place the first strand's end.
TEST(BodyPoint, AStrandsEndKeepsItsStrandAfterTheLayoutChanges) {
  auto scene = thread();
  CurveBody& body = *scene->bodies().front()->curve();
  scene->cut(body, 0.5);
  for (int k = 0; k < 20; ++k) ASSERT_TRUE(scene->step().ok);  // the strands move apart
  BasisRow end_row, start_row;
  body.basis().evaluateFromLeft(0.5, end_row);
  body.basis().evaluate(0.5, start_row);
  BodyPoint end, start;
  end.attach(body, 0.5, end_row, true);
  start.attach(body, 0.5, start_row);
  const VecX& q = scene->state().q;
  const Vec3 end_before = end.map(q), start_before = start.map(q);
  // Apart by far more than the 1e-15 m the checks below resolve, so that they tell the ends apart.
  ASSERT_GT((end_before - start_before).norm(), 1e-9) << "the two ends were expected apart after 20 steps";
  scene->refine(body, {0.2, 0.8});
  const VecX& refined = scene->state().q;
  // Knot insertion keeps each strand's curve: the ends where they were (round-off, 1e-15 m).
  EXPECT_LE((end.map(refined) - end_before).norm(), 1e-15);
  EXPECT_LE((start.map(refined) - start_before).norm(), 1e-15);
  const std::vector<Strand> pieces = strands(body.basis());
  ASSERT_EQ(pieces.size(), 2u);
  BasisRow first_strand_end;
  body.basis().evaluateFromLeft(0.5, first_strand_end);
  const PointWeights& w = end.weights();
  ASSERT_GT(w.count, 0);
  for (int j = 0; j < w.count; ++j)
    EXPECT_LT(w.point[j], first_strand_end.first + first_strand_end.count) << "a weight on the second strand";
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
