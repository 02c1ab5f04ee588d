// Scenes for the constraint tests, built as JSON documents and loaded through the same path as
// scene files: a short thread (10 cm, few control points, so that 10^5 RK4 steps take a second)
// with springs and damping, plus whatever constraints a test adds.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "filum/all_components.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"

namespace filum::test {

struct ConstraintThread {
  std::string name = "thread";
  int control_points = 8;
  double length = 0.1;                  // m, along +x from `origin`
  std::vector<double> origin{0, 0, 0};  // m
  double mass = 2.86e-6;                // kg (10 cm of 3-0 polypropylene)
  double stretch_stiffness = 1.0;       // N/m
  double bend_stiffness = 1e-3;         // N/m
  double viscous_damping = 0.5;         // 1/s
  // A vector, not a json array: "constraints = {c}" would copy c under clang (a one-element
  // braced list is a copy for nlohmann::json there, an array under gcc).
  std::vector<nlohmann::json> constraints;
};

inline nlohmann::json threadNode(const ConstraintThread& t) {
  using nlohmann::json;
  const json from = {t.origin[0], t.origin[1], t.origin[2]};
  const json to = {t.origin[0] + t.length, t.origin[1], t.origin[2]};
  json components = json::array();
  components.push_back({{"type", "DynamicSpline"},
                        {"control_points", {{"from", from}, {"to", to}, {"count", t.control_points}}},
                        {"mass", t.mass}});
  components.push_back({{"type", "SpringForceField"},
                        {"stretch_stiffness", t.stretch_stiffness},
                        {"bend_stiffness", t.bend_stiffness},
                        {"damping", 1e-5}});
  if (t.viscous_damping > 0) components.push_back({{"type", "ViscousDamping"}, {"coefficient", t.viscous_damping}});
  for (const auto& c : t.constraints) components.push_back(c);
  return json{{"name", t.name}, {"components", components}};
}

/// A scene of one or more threads; dt in s, gravity in m/s².
inline nlohmann::json constraintScene(const std::vector<ConstraintThread>& threads, double dt = 1e-4,
                                      const std::string& integrator = "RungeKutta4",
                                      std::vector<double> gravity = {0.0, 0.0, -9.81}) {
  using nlohmann::json;
  json nodes = json::array();
  for (const auto& t : threads) nodes.push_back(threadNode(t));
  return json{{"name", "constraint test"},
              {"dt", dt},
              {"gravity", gravity},
              {"integrator", {{"type", integrator}}},
              {"nodes", nodes}};
}

inline std::unique_ptr<Scene> loadConstraintScene(const nlohmann::json& document) {
  return loadScene(document, "constraint test", app::makeFactory());
}

/// Largest |violation| entry of the scene's active constraints over `steps` steps.
inline double maxViolationOver(Scene& scene, long steps) {
  double worst = 0.0;
  for (long k = 0; k < steps; ++k) {
    if (!scene.step().ok) return std::numeric_limits<double>::infinity();
    const VecX g = scene.constraintViolation(scene.state());
    if (g.size()) worst = std::max(worst, g.cwiseAbs().maxCoeff());
  }
  return worst;
}

}  // namespace filum::test
