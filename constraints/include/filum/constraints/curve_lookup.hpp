// The curve bodies constraints act on: their own body, or one named by node path (the target of
// an attachment, the other side of a junction), seen through the CurveBody interface. Every
// failure names the scene-file place and what was found.
#pragma once

#include <string>

#include "filum/core/component.hpp"
#include "filum/core/curve_body.hpp"

namespace filum {
class Scene;
}

namespace filum::constraints {

/// body as a curve (MechanicalState::curve()); throws SceneError at who's origin otherwise.
const CurveBody& requireCurve(const MechanicalState& body, const Component& who);

/// The curve body held by the node at `path` (from the root). `where` is the JSON place of the
/// path in the scene file; an unknown node lists the known ones.
const CurveBody& findCurve(const Scene& scene, const std::string& path, const std::string& where, const Component& who);

}  // namespace filum::constraints
