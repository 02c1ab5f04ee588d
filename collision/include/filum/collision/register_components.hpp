// Registers the collision library's components (issue 6; DESIGN.md "Libraries and their
// direction", 5): the sphere model of a spline, the obstacles (plane, sphere, capsule, triangle
// mesh, implicit surface), the scripted probe and the ContactPipeline (the default collision
// pipeline of a scene).
#pragma once

#include "filum/core/factory.hpp"

namespace filum::collision {

void register_components(Factory& factory);

}  // namespace filum::collision
