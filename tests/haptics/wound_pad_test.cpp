// WoundPad (haptics/wound_pad.hpp): the signed distance to a lip's slab against the rectangle's
// distance worked out by hand, at points inside (nearest face), outside beside a face and beyond a
// corner; nothing beyond the edge's ends; only the thread touches it, and not in its passage.
// Wound's scene block: every field refused at its JSON path.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "filum/collision/register_components.hpp"
#include "filum/constraints/register_components.hpp"
#include "filum/constraints/sliding_point_constraint.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/haptics/instrument_set.hpp"
#include "filum/haptics/wound_pad.hpp"
#include "filum/mechanics/register_components.hpp"

namespace filum::haptics {
namespace {

using nlohmann::json;

// One lip: its edge along x from 0 to 0.04 at y = −0.002, z = −0.001 (edge radius 1 mm), ô = −y
// (away from the wound at y = 0), n̂ = +z; the slab 15 mm wide and 5 mm thick: the cut face at
// y = −0.001, the far side at y = −0.016, the skin at z = 0, the bottom at z = −0.005.
WoundPad straightPad() {
  WoundPad pad(0.015, 0.005, 0.001);
  std::vector<WoundPad::Station> edge(5);
  for (int i = 0; i < 5; ++i) {
    edge[i].point = Vec3(0.01 * i, -0.002, -0.001);
    edge[i].tangent = Vec3::UnitX();
    edge[i].normal = Vec3::UnitZ();
    edge[i].outward = -Vec3::UnitY();
    edge[i].velocity = Vec3(0, 0, 0.1);
  }
  pad.setEdges(edge, {});
  return pad;
}

TEST(WoundPad, SignedDistanceToTheSlabIsTheRectangles) {
  const WoundPad pad = straightPad();
  collision::SurfaceSample s;
  // Inside, 0.3 mm under the skin and 4 mm from the cut face: the skin is nearest.
  ASSERT_TRUE(pad.sample(Vec3(0.02, -0.005, -0.0003), 1.0, s));
  EXPECT_NEAR(s.distance, -0.0003, 1e-15);
  EXPECT_NEAR((s.normal - Vec3::UnitZ()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((s.point - Vec3(0.02, -0.005, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((s.velocity - Vec3(0, 0, 0.1)).norm(), 0.0, 1e-15);
  // Inside, 0.2 mm from the cut face and 2 mm deep: the cut face is nearest, its normal +y.
  ASSERT_TRUE(pad.sample(Vec3(0.02, -0.0012, -0.002), 1.0, s));
  EXPECT_NEAR(s.distance, -0.0002, 1e-15);
  EXPECT_NEAR((s.normal - Vec3::UnitY()).norm(), 0.0, 1e-15);
  // Outside above the skin by 1 mm.
  ASSERT_TRUE(pad.sample(Vec3(0.03, -0.01, 0.001), 1.0, s));
  EXPECT_NEAR(s.distance, 0.001, 1e-15);
  EXPECT_NEAR((s.normal - Vec3::UnitZ()).norm(), 0.0, 1e-15);
  // Outside beyond the corner of the cut face and the skin: 0.3 mm across and 0.4 mm up, 0.5 mm away.
  ASSERT_TRUE(pad.sample(Vec3(0.03, -0.0007, 0.0004), 1.0, s));
  EXPECT_NEAR(s.distance, 0.0005, 1e-15);
  EXPECT_NEAR((s.normal - Vec3(0, 0.6, 0.8)).norm(), 0.0, 1e-12);
  // Farther than asked: nothing. Beyond the edge's ends: no skin.
  EXPECT_FALSE(pad.sample(Vec3(0.03, -0.01, 0.002), 0.001, s));
  EXPECT_FALSE(pad.sample(Vec3(-0.001, -0.005, -0.0003), 1.0, s));
  EXPECT_FALSE(pad.sample(Vec3(0.041, -0.005, -0.0003), 1.0, s));
}

TEST(WoundPad, OnlyTheThreadTouchesItAndNotInItsPassage) {
  // Two bodies: the pad lets any body but the thread through, and the thread within its spans.
  json scene{{"name", "pad"}, {"dt", 1e-3}, {"duration", 0.01}, {"gravity", {0, 0, 0}},
             {"nodes", json::array({{{"name", "thread"},
                                     {"components", json::array({{{"type", "DynamicSpline"},
                                                                  {"control_points", {{"from", {0, 0, 0}}, {"to", {0.1, 0, 0}}, {"count", 8}}},
                                                                  {"radius", 1e-4}, {"density", 910}}})}},
                                    {{"name", "lip"},
                                     {"components", json::array({{{"type", "DynamicSpline"},
                                                                  {"control_points", {{"from", {0, 1, 0}}, {"to", {0.1, 1, 0}}, {"count", 8}}},
                                                                  {"radius", 1e-3}, {"density", 1000}}})}}})}};
  Factory factory;
  mechanics::register_components(factory);
  auto s = loadScene(scene, "pad test", factory);
  const CurveBody& thread = *s->bodies()[0]->curve();
  const CurveBody& lip = *s->bodies()[1]->curve();
  WoundPad pad = straightPad();
  pad.setPassage(&thread, {{0.2, 0.3}});
  EXPECT_TRUE(pad.passesThrough(lip, 0.5));
  EXPECT_TRUE(pad.passesThrough(thread, 0.25));
  EXPECT_FALSE(pad.passesThrough(thread, 0.35));
  EXPECT_FALSE(pad.passesThrough(thread, 0.1));
}

TEST(Wound, EveryFieldIsRefusedAtItsJsonPath) {
  const json lip = {{"type", "DynamicSpline"}, {"control_points", {{"from", {-0.02, -0.002, -0.001}}, {"to", {0.02, -0.002, -0.001}}, {"count", 8}}},
                    {"radius", 0.003}, {"density", 1000}};
  json lip2 = lip;
  lip2["control_points"]["from"] = {-0.02, 0.002, -0.001};
  lip2["control_points"]["to"] = {0.02, 0.002, -0.001};
  const json thread = {{"type", "DynamicSpline"}, {"control_points", {{"from", {0, 0, 0.01}}, {"to", {0.1, 0, 0.01}}, {"count", 10}}},
                       {"radius", 1e-4}, {"density", 910}};
  const json good_wound = {{"lips", {"left", "right"}}, {"thread", "suture"}, {"edge_radius", 0.001}};
  json thread_components = json::array({thread, {{"type", "SphereCollisionModel"}, {"spacing", 2e-4}, {"self_collision", false}}});
  // A needle carrying the thread, lying away from the wound.
  const json needle = {{"name", "needle"}, {"radius", 0.008}, {"arc", 2.356}, {"center", {0.1, 0.0, 0.018}},
                       {"normal", {0, 1, 0}}, {"start", {-1, 0, 0}}, {"thread", "suture"}, {"abscissa", 1.0}};
  auto document = [&](const json& wound) {
    return json{{"name", "wound test"}, {"dt", 1e-3}, {"duration", 0.01}, {"gravity", {0, 0, 0}},
                {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}}},
                {"nodes", json::array({{{"name", "suture"}, {"components", thread_components}},
                                       {{"name", "left"}, {"components", json::array({lip})}},
                                       {{"name", "right"}, {"components", json::array({lip2})}}})},
                {"wound", wound},
                {"needles", json::array({needle})},
                {"instruments", json::array({{{"name", "holder"}, {"type", "NeedleHolder"}, {"collide", false},
                                              {"path", json::array({{{"time", 0}, {"position", {0, 0, 0.05}}, {"direction", {0, 0, -1}}}})}}})}};
  };
  Factory factory;
  mechanics::register_components(factory);
  constraints::register_components(factory);
  collision::register_components(factory);
  {
    const json doc = document(good_wound);
    auto scene = loadScene(doc, "wound test", factory);
    auto set = InstrumentSet::fromScene(doc, "wound test", *scene);
    ASSERT_NE(set->wound(), nullptr);
    EXPECT_EQ(set->wound()->slots().size(), 4u);  // two per lip by default, inactive
    for (const auto* c : set->wound()->slots()) EXPECT_FALSE(c->active());
    EXPECT_NEAR(set->wound()->gap(scene->state()), 0.002, 1e-15);  // edges 4 mm apart, less 2 r_e
  }
  struct Case {
    const char* key;
    json value;
    const char* where;
  };
  const std::vector<Case> cases = {
      {"lips", json::array({"left"}), "/wound/lips"},
      {"lips", json::array({"left", "left"}), "/wound/lips"},
      {"lips", json::array({"left", "nowhere"}), "/wound/lips"},
      {"thread", "left", "/wound/thread"},
      {"thread", "nowhere", "/wound/thread"},
      {"normal", json::array({0, 0, 0}), "/wound/normal"},
      {"width", -1.0, "/wound/width"},
      {"edge_radius", 0.003, "/wound/edge_radius"},
      {"puncture_force", 0.0, "/wound/puncture_force"},
      {"holes_per_lip", 0, "/wound/holes_per_lip"},
      {"holes_per_lip", 65, "/wound/holes_per_lip"},
      {"friction", -1.0, "/wound/friction"},
      {"engage_distance", 0.0, "/wound/engage_distance"},
      {"thickness", 0.0, "/wound/thickness"},
      {"indentation_stiffness", -5.0, "/wound/indentation_stiffness"},
      {"targets", json::array({json::array({0, 0})}), "/wound/targets"},
      {"normal", json::array({1, 0, 0}), "/wound/normal"},  // along the lips' edges: no side
      {"colour", 1.0, "/wound/colour"},
  };
  for (const Case& c : cases) {
    json wound = good_wound;
    wound[c.key] = c.value;
    const json doc = document(wound);
    auto scene = loadScene(doc, "wound test", factory);
    try {
      InstrumentSet::fromScene(doc, "wound test", *scene);
      ADD_FAILURE() << c.key << " = " << c.value.dump() << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(c.where), std::string::npos) << c.key << ": " << e.what();
    }
  }
  // What the wound needs from the rest of the scene: a needle carrying its thread, a collision
  // model on the thread (the loader always makes a collision pipeline: the factory's default).
  struct Missing {
    const char* what;
    std::function<void(json&)> remove;
    const char* where;
  };
  const std::vector<Missing> missing = {
      {"no needle carries the thread", [](json& d) { d["needles"][0]["thread"] = "left"; }, "/wound/thread"},
      {"no collision model on the thread",
       [](json& d) { d["nodes"][0]["components"].erase(1); }, "/wound/thread"},
  };
  for (const Missing& m : missing) {
    json doc = document(good_wound);
    m.remove(doc);
    auto scene = loadScene(doc, "wound test", factory);
    try {
      InstrumentSet::fromScene(doc, "wound test", *scene);
      ADD_FAILURE() << m.what << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(m.where), std::string::npos) << m.what << ": " << e.what();
    }
  }
}

}  // namespace
}  // namespace filum::haptics
