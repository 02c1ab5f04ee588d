// Registers the constraints library's components: FixedPointConstraint, PointOnAxisConstraint,
// PointOnPlaneConstraint, ClampConstraint, SlidingPointConstraint, SplineJunctionConstraint and
// LagrangeMultiplierSolver (the default constraint solver).
#pragma once

#include "filum/core/factory.hpp"

namespace filum::constraints {

void register_components(Factory& factory);

}  // namespace filum::constraints
