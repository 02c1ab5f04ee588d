// Registers the collision library's components (docs/architecture.md, "Libraries, top to
// bottom": collision/): the sphere model of a spline, the obstacles (plane, sphere, capsule, triangle
// mesh, implicit surface), the scripted probe and the ContactPipeline (the default collision
// pipeline of a scene).
#pragma once

#include "filum/core/factory.hpp"

namespace filum::collision {

void register_components(Factory& factory);

}  // namespace filum::collision
