// Registers the mechanics library's components: DynamicSpline; the force fields
// SpringForceField, GreenLagrangeStretching, GlobalStretching, ParametricBending,
// CurvatureBending, ViscousDamping, RayleighDamping; the integrators ExplicitEuler,
// SymplecticEuler, RungeKutta4 (default), ImplicitEuler, ImplicitMidpoint.
#pragma once

#include "filum/core/factory.hpp"

namespace filum::mechanics {

void register_components(Factory& factory);

}  // namespace filum::mechanics
