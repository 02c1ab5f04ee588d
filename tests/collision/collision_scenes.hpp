// Scenes for the collision tests, built as JSON documents and loaded through the same path as
// scene files: threads (DynamicSpline + springs + damping + a SphereCollisionModel) with any
// constraints, obstacles at the root, and the "collision" block of the ContactPipeline.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "filum/all_components.hpp"
#include "filum/collision/contact_pipeline.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"

namespace filum::test {

struct CollisionThread {
  std::string name = "thread";
  nlohmann::json control_points;        // [[x, y, z], ...] or {"from", "to", "count"}
  double mass = 1e-4;                   // kg
  double radius = 1e-3;                 // m (mechanical and collision)
  double stretch_stiffness = 20.0;      // N/m
  double bend_stiffness = 0.05;         // N/m
  double spring_damping = 1e-4;         // N·s/m
  double viscous_damping = 1.0;         // 1/s
  bool collision = true;
  nlohmann::json collision_params = nlohmann::json::object();  // extra SphereCollisionModel parameters
  nlohmann::json constraints = nlohmann::json::array();
};

inline nlohmann::json collisionThreadNode(const CollisionThread& t) {
  using nlohmann::json;
  json components = json::array();
  components.push_back({{"type", "DynamicSpline"}, {"control_points", t.control_points}, {"mass", t.mass},
                        {"radius", t.radius}});
  components.push_back({{"type", "SpringForceField"},
                        {"stretch_stiffness", t.stretch_stiffness},
                        {"bend_stiffness", t.bend_stiffness},
                        {"damping", t.spring_damping}});
  if (t.viscous_damping > 0) components.push_back({{"type", "ViscousDamping"}, {"coefficient", t.viscous_damping}});
  if (t.collision) {
    json model = {{"type", "SphereCollisionModel"}};
    for (auto it = t.collision_params.begin(); it != t.collision_params.end(); ++it) model[it.key()] = it.value();
    components.push_back(model);
  }
  for (const auto& c : t.constraints) components.push_back(c);
  return json{{"name", t.name}, {"components", components}};
}

/// A scene of threads and root components (obstacles); `collision` is the ContactPipeline block.
inline nlohmann::json collisionScene(const std::vector<CollisionThread>& threads, const nlohmann::json& collision,
                                     double dt = 1e-4, const nlohmann::json& root_components = nlohmann::json::array(),
                                     std::vector<double> gravity = {0.0, 0.0, -9.81}) {
  using nlohmann::json;
  json nodes = json::array();
  for (const auto& t : threads) nodes.push_back(collisionThreadNode(t));
  json scene = {{"name", "collision test"}, {"dt", dt}, {"gravity", gravity},
                {"integrator", {{"type", "RungeKutta4"}}}, {"collision", collision}, {"nodes", nodes}};
  if (!root_components.empty()) scene["components"] = root_components;
  return scene;
}

inline std::unique_ptr<Scene> loadCollisionScene(const nlohmann::json& document) {
  static const Factory factory = app::makeFactory();
  return loadScene(document, "collision test", factory);
}

inline const collision::ContactPipeline& pipelineOf(const Scene& scene) {
  return dynamic_cast<const collision::ContactPipeline&>(*scene.collisionPipeline());
}

}  // namespace filum::test
