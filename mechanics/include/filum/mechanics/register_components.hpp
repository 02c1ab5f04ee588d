// Registers the mechanics library's components: DynamicSpline, SpringForceField,
// ViscousDamping, SymplecticEuler, RungeKutta4 (default integrator).
#pragma once

#include "filum/core/factory.hpp"

namespace filum::mechanics {

void register_components(Factory& factory);

}  // namespace filum::mechanics
