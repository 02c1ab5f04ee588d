#include "filum/mechanics/register_components.hpp"

#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/mechanics/runge_kutta4.hpp"
#include "filum/mechanics/spring_force_field.hpp"
#include "filum/mechanics/symplectic_euler.hpp"
#include "filum/mechanics/viscous_damping.hpp"

namespace filum::mechanics {

void register_components(Factory& factory) {
  factory.add("DynamicSpline", "dynamic Lagrangian spline: control points as DOFs, banded mass (paper §3)",
              [](const Params& p) { return DynamicSpline::fromParams(p); });
  factory.add("SpringForceField", "stretch and bend springs between points sampled on the curve (paper Fig. 1)",
              [](const Params& p) { return SpringForceField::fromParams(p); });
  factory.add("ViscousDamping", "mass-proportional viscous drag Q = -gamma M v",
              [](const Params& p) { return ViscousDamping::fromParams(p); });
  factory.add("SymplecticEuler", "semi-implicit Euler, first order, symplectic",
              [](const Params& p) { return SymplecticEuler::fromParams(p); });
  factory.add("RungeKutta4", "classical fourth-order Runge-Kutta (paper §3)",
              [](const Params& p) { return RungeKutta4::fromParams(p); });
  factory.setDefault("Integrator", "RungeKutta4");
}

}  // namespace filum::mechanics
