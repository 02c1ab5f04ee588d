// Small scenes built in code for the tests: a straight thread with springs, optional damping and
// a fixed end, as a JSON document loaded through the same path as scene files.
#pragma once

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "filum/all_components.hpp"
#include "filum/core/scene_loader.hpp"

namespace filum::test {

struct ThreadSceneOptions {
  int control_points = 30;
  std::string integrator = "RungeKutta4";
  double dt = 1e-4;                 // s
  double length = 0.1;              // m, along +x from the origin
  double mass = 2.86e-6;            // kg (10 cm of 3-0 polypropylene)
  double stretch_stiffness = 1.0;   // N/m
  double bend_stiffness = 1e-3;     // N/m
  double spring_damping = 0.0;      // N·s/m
  double viscous_damping = 0.0;     // 1/s
  bool fixed_start = true;          // hold P(0) where it starts
  bool springs = true;
};

inline nlohmann::json threadScene(const ThreadSceneOptions& o) {
  using nlohmann::json;
  json components = json::array();
  components.push_back({{"type", "DynamicSpline"},
                        {"control_points", {{"from", {0.0, 0.0, 0.0}}, {"to", {o.length, 0.0, 0.0}}, {"count", o.control_points}}},
                        {"mass", o.mass}});
  if (o.springs)
    components.push_back({{"type", "SpringForceField"},
                          {"stretch_stiffness", o.stretch_stiffness},
                          {"bend_stiffness", o.bend_stiffness},
                          {"damping", o.spring_damping}});
  if (o.viscous_damping > 0.0) components.push_back({{"type", "ViscousDamping"}, {"coefficient", o.viscous_damping}});
  if (o.fixed_start) components.push_back({{"type", "FixedPointConstraint"}, {"abscissa", 0.0}});
  return json{{"name", "test thread"},
              {"dt", o.dt},
              {"gravity", {0.0, 0.0, -9.81}},
              {"integrator", {{"type", o.integrator}}},
              {"nodes", json::array({json{{"name", "thread"}, {"components", components}}})}};
}

inline std::unique_ptr<Scene> loadThreadScene(const ThreadSceneOptions& o) {
  return loadScene(threadScene(o), "test thread", app::makeFactory());
}

}  // namespace filum::test
