// Scene-file errors of the collision components name the file, the JSON place, what was expected
// and what was found — refused before the simulation starts, like every other component.
#include <gtest/gtest.h>

#include "collision_scenes.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::collision {
namespace {

/// The message of the SceneError that loading `document` throws ("" if it loads).
std::string errorOf(const nlohmann::json& document) {
  try {
    test::loadCollisionScene(document);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

test::CollisionThread thread() {
  test::CollisionThread t;
  t.control_points = {{"from", {0, 0, 0}}, {"to", {0.1, 0, 0}}, {"count", 8}};
  return t;
}

TEST(CollisionSceneErrors, NameTheFileThePlaceAndWhatWasExpected) {
  const nlohmann::json pipeline = {{"type", "ContactPipeline"}};
  struct Case {
    nlohmann::json document;
    std::vector<std::string> parts;
  };
  std::vector<Case> cases;

  nlohmann::json bad_response = test::collisionScene({thread()}, {{"type", "ContactPipeline"}, {"response", "sticky"}});
  cases.push_back({bad_response, {"collision test: /collision/response", "\"penalty\" or \"unilateral\"", "\"sticky\""}});

  cases.push_back({test::collisionScene({thread()}, {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"max_penetration", 1.0}}),
                   {"/collision/max_penetration", "a fraction of the contact distance in [0, 1)", "1"}});
  cases.push_back({test::collisionScene({thread()}, {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"contact_halvings", 6}}),
                   {"/collision/contact_halvings", "at most 5", "6"}});
  cases.push_back({test::collisionScene({thread()}, {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"max_slide", -1e-4}}),
                   {"/collision/max_slide", "a number >= 0", "-0.0001"}});

  test::CollisionThread wide = thread();
  wide.collision_params = {{"spacing", 0.005}};  // radius 1 mm
  cases.push_back({test::collisionScene({wide}, pipeline),
                   {"/nodes/0/components/3/spacing", "a spacing <= 2 radius", "0.005"}});

  test::CollisionThread negative = thread();
  negative.collision_params = {{"radius", -1e-3}};
  cases.push_back({test::collisionScene({negative}, pipeline), {"/nodes/0/components/3/radius", "a positive number", "-0.001"}});

  nlohmann::json loose = test::collisionScene({thread()}, pipeline);
  loose["components"] = nlohmann::json::array({{{"type", "SphereCollisionModel"}}});
  cases.push_back({loose, {"/components/0", "belongs in the node of a curve body such as a DynamicSpline", "no body"}});

  cases.push_back({test::collisionScene({thread()}, pipeline, 1e-4,
                                        nlohmann::json::array({{{"type", "PlaneObstacle"}, {"friction", -0.2}}})),
                   {"/components/0/friction", "a number >= 0", "-0.2"}});

  cases.push_back({test::collisionScene({thread()}, pipeline, 1e-4,
                                        nlohmann::json::array({{{"type", "ProbeSphere"}, {"radius", 0.005}}})),
                   {"/components/0/path", "nothing (the parameter is missing)"}});

  cases.push_back({test::collisionScene({thread()}, pipeline, 1e-4,
                                        nlohmann::json::array({{{"type", "PlaneObstacle"}, {"normal", {0, 0, 0}}}})),
                   {"/components/0/normal", "a non-zero normal"}});

  for (const Case& c : cases) {
    const std::string message = errorOf(c.document);
    ASSERT_FALSE(message.empty()) << "accepted: " << c.document.dump();
    for (const std::string& part : c.parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace filum::collision
