// Scenes for the mechanics tests: one straight thread (a DynamicSpline along +x from the origin)
// with any list of components, loaded from JSON through the same path as scene files.
#pragma once

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "filum/all_components.hpp"
#include "filum/core/scene.hpp"
#include "validation/stability.hpp"
#include "filum/core/scene_loader.hpp"

namespace filum::test {

struct ThreadSpec {
  int control_points = 8;
  double length = 0.1;                  // m
  double mass = 2.86e-6;                // kg: 10 cm of 3-0 polypropylene (ρ = 910, r = 1e-4)
  double radius = 1e-4;                 // m
  nlohmann::json integrator = {{"type", "ImplicitEuler"}};
  double dt = 1e-4;                     // s
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};
};

inline nlohmann::json threadWith(const ThreadSpec& spec, const nlohmann::json& more_components) {
  using nlohmann::json;
  json components = json::array();
  components.push_back({{"type", "DynamicSpline"},
                        {"control_points",
                         {{"from", {0.0, 0.0, 0.0}}, {"to", {spec.length, 0.0, 0.0}}, {"count", spec.control_points}}},
                        {"mass", spec.mass},
                        {"radius", spec.radius}});
  for (const auto& c : more_components) components.push_back(c);
  return json{{"name", "mechanics test thread"},
              {"dt", spec.dt},
              {"gravity", {spec.gravity.x(), spec.gravity.y(), spec.gravity.z()}},
              {"integrator", spec.integrator},
              {"nodes", json::array({json{{"name", "thread"}, {"components", components}}})}};
}

inline std::unique_ptr<Scene> loadThreadWith(const ThreadSpec& spec, const nlohmann::json& more_components) {
  static const Factory factory = app::makeFactory();
  return loadScene(threadWith(spec, more_components), "mechanics test thread", factory);
}

/// ω_max (rad/s) of the linearized dynamics at state s (apps/validation/stability.hpp).
using validation::stiffestFrequency;

}  // namespace filum::test
