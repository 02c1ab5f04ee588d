#include "filum/constraints/spline_body.hpp"

#include <vector>

#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::constraints {

const mechanics::DynamicSpline& requireSpline(const MechanicalState& body, const Component& who) {
  const auto* spline = dynamic_cast<const mechanics::DynamicSpline*>(&body);
  if (!spline) throw SceneError(who.origin(), "a DynamicSpline body for " + who.describe(), body.describe());
  return *spline;
}

const mechanics::DynamicSpline& findSpline(const Scene& scene, const std::string& path, const std::string& where,
                                           const Component& who) {
  const MechanicalState* body = path.empty() ? nullptr : scene.bodyAt(path);
  if (!body) {
    std::vector<std::string> paths;
    scene.root().listPaths(paths);
    std::string known;
    bool exists = false;
    for (const auto& p : paths) {
      if (!p.empty()) known += (known.empty() ? "" : ", ") + p;
      exists = exists || p == path;
    }
    throw SceneError(where, "the path of a node holding a DynamicSpline (known nodes: " + known + ")",
                     "\"" + path + "\"" + (exists ? ", a node without a mechanical state" : ""));
  }
  const auto* spline = dynamic_cast<const mechanics::DynamicSpline*>(body);
  if (!spline) throw SceneError(where, "a node holding a DynamicSpline for " + who.describe(), body->describe());
  return *spline;
}

}  // namespace filum::constraints
