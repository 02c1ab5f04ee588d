// Spline bodies of constraints: the DynamicSpline a constraint acts on (its own body, or one
// named by node path, e.g. the target of an attachment or the other side of a junction), and
// the basis rows at an abscissa. Every failure names the scene-file place and what was found.
#pragma once

#include <string>

#include "filum/core/component.hpp"
#include "filum/core/mechanical_state.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum {
class Scene;
}

namespace filum::constraints {

/// body as a DynamicSpline; throws SceneError at who's origin otherwise.
const mechanics::DynamicSpline& requireSpline(const MechanicalState& body, const Component& who);

/// The DynamicSpline held by the node at `path` (from the root). `where` is the JSON place of
/// the path in the scene file; an unknown node lists the known ones.
const mechanics::DynamicSpline& findSpline(const Scene& scene, const std::string& path, const std::string& where,
                                           const Component& who);

}  // namespace filum::constraints
