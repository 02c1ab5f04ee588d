// No pass-through: threads driven across each other at 2 m/s, and a knot pulled tight at 2 m/s
// (a thread pulled against itself), never cross — in both contact responses. The check
// (crossing_watch.hpp) is independent of the pipeline: segments of polylines sampled on the
// material never meet between two steps, and the crossing sign of every close pair is kept.
#include <iostream>
#include <map>

#include <gtest/gtest.h>

#include "collision_scenes.hpp"
#include "crossing_watch.hpp"
#include "filum/collision/segment_closest_points.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum::collision {
namespace {

using test::CrossingWatch;
using test::kSamples;
using test::watch;


nlohmann::json pipelineSettings(const std::string& response) {
  // Penalty: k = 500 N/m stops 2 m/s within v √(m/k) ≈ 0.3 mm for m ≈ 1e-5 kg per control
  // point (ω dt = 0.7 at dt = 1e-4, inside RK4's stability); the damper is near critical.
  if (response == "penalty") return {{"type", "ContactPipeline"}, {"response", "penalty"}, {"stiffness", 500.0}, {"damping", 0.02}};
  return {{"type", "ContactPipeline"}, {"response", "unilateral"}};
}

class NoPassThrough : public ::testing::TestWithParam<std::string> {};

TEST_P(NoPassThrough, TwoThreadsDrivenAcrossEachOtherAtTwoMetresPerSecondNeverCross) {
  // A along x, ends fixed; B along y, 4 mm above, both ends driven down at 2 m/s through A's
  // line for 15 ms (30 mm), its control points starting at −2 m/s too.
  const double r = 1e-3, v = 2.0, drive = 0.015;
  test::CollisionThread a;
  a.name = "a";
  a.control_points = {{"from", {-0.05, 0.0, 0.0}}, {"to", {0.05, 0.0, 0.0}}, {"count", 10}};
  a.radius = r;
  a.constraints = {{{"type", "FixedPointConstraint"}, {"abscissa", 0.0}}, {{"type", "FixedPointConstraint"}, {"abscissa", 1.0}}};
  test::CollisionThread b = a;
  b.name = "b";
  b.control_points = {{"from", {0.0, -0.05, 0.004}}, {"to", {0.0, 0.05, 0.004}}, {"count", 10}};
  b.constraints.clear();
  for (double end : {0.0, 1.0}) {
    const double y = end == 0.0 ? -0.05 : 0.05;
    b.constraints.push_back({{"type", "FixedPointConstraint"},
                             {"abscissa", end},
                             {"path", {{{"time", 0.0}, {"position", {0.0, y, 0.004}}},
                                       {{"time", drive}, {"position", {0.0, y, 0.004 - v * drive}}}}}});
  }
  auto scene = test::loadCollisionScene(test::collisionScene({a, b}, pipelineSettings(GetParam()), 1e-4,
                                                             nlohmann::json::array(), {0.0, 0.0, 0.0}));
  SceneState s = scene->state();
  const MechanicalState& body_b = *scene->bodies()[1];
  for (int i = 0; i < body_b.pointCount(); ++i) s.v[3 * (body_b.offset() + i) + 2] = -v;
  scene->setState(s);

  const CrossingWatch w = watch(*scene, 300, 8, r);  // 30 ms
  std::cout << "  " << GetParam() << ": closest centre lines " << w.min_distance * 1e3 << " mm (contact at "
            << 2e3 * r << " mm), " << w.close_pairs << " close pair-steps, " << w.sign_flips << " sign flips, "
            << w.crossings << " crossings\n";
  EXPECT_EQ(w.crossings, 0);
  EXPECT_EQ(w.sign_flips, 0);
  EXPECT_GT(w.close_pairs, 100);  // the threads did press on each other
  EXPECT_GT(w.min_distance, r);   // at most half the contact distance lost to penetration
  // B went 30 mm down: A was carried along below it.
  const Points curve_a = CrossingWatch::sample(*scene, scene->state()).topRows(kSamples);
  EXPECT_LT(curve_a.col(2).minCoeff(), -0.02);
}

TEST_P(NoPassThrough, AKnotPulledTightAtTwoMetresPerSecondNeverCrossesItself) {
  // The open overhand knot of apps/scenes/paper_knot.json, its right end pulled 6 cm away at 2 m/s
  // from the start: the knot closes on itself at once, strands pressed against strands.
  nlohmann::json document = readJsonFile(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/paper_knot.json");
  document["collision"] = pipelineSettings(GetParam());
  for (auto& c : document["nodes"][0]["components"])
    if (c.value("name", "") == "right end")
      c["path"] = {{{"time", 0.0}, {"position", {0.0416, -0.0075, 0.0185}}},
                   {{"time", 0.03}, {"position", {0.1016, -0.0075, 0.0185}}}};
  auto scene = loadScene(document, "paper_knot.json pulled at 2 m/s", app::makeFactory());
  const double r = test::pipelineOf(*scene).models().front()->radius();
  // 120 samples on 23 cm: segments less than 8 samples (1.5 cm) apart along the thread are
  // neighbours (the tightest loop of the knot is about 7 cm around).
  const CrossingWatch w = watch(*scene, 600, 8, r);  // 60 ms
  std::cout << "  " << GetParam() << ": closest centre lines " << w.min_distance * 1e3 << " mm (contact at "
            << 2e3 * r << " mm), " << w.close_pairs << " close pair-steps, " << w.sign_flips << " sign flips, "
            << w.crossings << " crossings\n";
  EXPECT_EQ(w.crossings, 0);
  EXPECT_EQ(w.sign_flips, 0);
  EXPECT_GT(w.close_pairs, 100);  // the strands did press on each other
  EXPECT_GT(w.min_distance, r);
}

INSTANTIATE_TEST_SUITE_P(Responses, NoPassThrough, ::testing::Values("penalty", "unilateral"));

}  // namespace
}  // namespace filum::collision

namespace filum::collision {
namespace {

TEST(MissedContact, NeighbouringChordsAndABodyWithoutSelfCollisionAreNotPassThroughs) {
  // Two straight threads 4 cm apart at rest, beside each other: nothing moves through anything.
  // The first has spheres exactly 2 r apart, so that the bound on two neighbouring chords' distance
  // along it, 2 h = 4 r, equals the exclusion 4 r: they share a sphere, their centre lines meet
  // there, and the end-of-step check (missedContact) must skip them as the contact search does.
  // The second has no self-collision: its own chords are never checked. Before both were skipped
  // the first step faulted ("a thread passed through another").
  for (const bool self : {true, false}) {
    const double r = 1e-4;
    const auto thread = [&](const std::string& name, double y, bool self_collision) {
      return nlohmann::json{
          {"name", name},
          {"components", nlohmann::json::array(
                             {{{"type", "DynamicSpline"},
                               {"control_points", {{"from", {0, y, 0}}, {"to", {0.1, y, 0}}, {"count", 20}}},
                               {"radius", r}, {"density", 910}},
                              {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}},
                              {{"type", "SphereCollisionModel"}, {"spacing", 2 * r}, {"self_collision", self_collision}},
                              {{"type", "FixedPointConstraint"}, {"abscissa", 0.0}},
                              {{"type", "FixedPointConstraint"}, {"abscissa", 1.0}}})}};
    };
    const nlohmann::json document{
        {"name", "missed contact"}, {"dt", 1e-3}, {"duration", 0.01}, {"gravity", {0, 0, 0}},
        {"integrator", {{"type", "ImplicitEuler"}}},
        {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}}},
        {"nodes", nlohmann::json::array({thread("a", 0.0, self), thread("b", 0.04, false)})}};
    auto scene = loadScene(document, "missed contact", app::makeFactory());
    for (int k = 0; k < 10; ++k) {
      const StepReport report = scene->step();
      ASSERT_TRUE(report.ok) << "self-collision " << self << ", step " << k << ": " << report.message;
    }
  }
}

}  // namespace
}  // namespace filum::collision
