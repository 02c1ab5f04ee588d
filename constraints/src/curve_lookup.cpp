#include "filum/constraints/curve_lookup.hpp"

#include <vector>

#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::constraints {

const CurveBody& requireCurve(const MechanicalState& body, const Component& who) {
  const CurveBody* curve = body.curve();
  if (!curve) throw SceneError(who.origin(), "a curve body (e.g. a DynamicSpline) for " + who.describe(), body.describe());
  return *curve;
}

const CurveBody& findCurve(const Scene& scene, const std::string& path, const std::string& where, const Component& who) {
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
    throw SceneError(where, "the path of a node holding a curve body, e.g. a DynamicSpline (known nodes: " + known + ")",
                     "\"" + path + "\"" + (exists ? ", a node without a mechanical state" : ""));
  }
  const CurveBody* curve = body->curve();
  if (!curve) throw SceneError(where, "a node holding a curve body (e.g. a DynamicSpline) for " + who.describe(), body->describe());
  return *curve;
}

}  // namespace filum::constraints
