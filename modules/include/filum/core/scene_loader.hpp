// Scene files: JSON (comments allowed), a tree of nodes each listing components by type name
// with their parameters. Everything is checked before the simulation starts.
//
//   {
//     "name": "hanging thread", "dt": 1e-4, "duration": 3, "gravity": [0, 0, -9.81],
//     "integrator": {"type": "RungeKutta4"},
//     "nodes": [ {"name": "thread", "components": [ {"type": "DynamicSpline", ...} ],
//                 "nodes": [ ...children... ]} ]
//   }
#pragma once

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "filum/core/factory.hpp"
#include "filum/core/scene.hpp"

namespace filum {

/// Reads, checks and initialises a scene file. Throws SceneError.
std::unique_ptr<Scene> loadScene(const std::string& path, const Factory& factory);

/// Same from an already parsed document; `source` names it in messages.
std::unique_ptr<Scene> loadScene(const nlohmann::json& document, const std::string& source,
                                 const Factory& factory);

/// Parses a JSON file with comments; syntax errors name the file, line and column.
nlohmann::json readJsonFile(const std::string& path);

}  // namespace filum
