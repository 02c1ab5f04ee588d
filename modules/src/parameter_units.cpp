#include "filum/core/parameter_units.hpp"

#include <map>

namespace filum {

std::string commonParameterUnit(const std::string& key) {
  // Keys that mean one quantity wherever they are read. Where a key's unit depends on the type
  // (a "stiffness", a "damping", a "tolerance"), the type says it (Factory::addUnits).
  static const std::map<std::string, std::string> units = {
      {"abscissa", "1"},  // the curve's parametric abscissa s in [0, 1]
      {"abscissas", "1"},
      {"angular_velocities", "rad/s"},
      {"approximation", "m"},
      {"axis", "1"},  // a direction: normalized by the component
      {"bend_stiffness", "N/m"},
      {"break_force", "N"},
      {"cell_size", "m"},
      {"center", "m"},
      {"coarsen_angle", "rad"},
      {"color", "1"},  // red, green, blue in [0, 1]
      {"contact_compliance", "1"},  // relative to the Delassus diagonal
      {"contact_tolerance", "1"},
      {"control_points", "m"},
      {"density", "kg/m³"},
      {"direction", "1"},
      {"drop_tolerance", "1"},
      {"exclusion", "m"},
      {"facet_size", "m"},
      {"force", "N"},
      {"friction", "1"},  // Coulomb's coefficient μ
      {"friction_compliance", "1"},
      {"friction_rate", "1/s"},
      {"friction_velocity", "m/s"},
      {"knots", "1"},
      {"linearization_tolerance", "1"},
      {"margin", "m"},
      {"mass", "kg"},
      {"max_penetration", "1"},
      {"max_slide", "m"},
      {"min_span", "m"},
      {"newton_damping", "1"},
      {"newton_tolerance", "1"},
      {"normal", "1"},
      {"opacity", "1"},
      {"path", "s, m"},  // keyframes: time (s), position (m)
      {"point", "m"},
      {"poisson_ratio", "1"},
      {"radius", "m"},
      {"radius_profile", "1, m"},  // [u, r]: u a fraction of the length, r (m)
      {"refine_angle", "rad"},
      {"release_at", "s"},
      {"rest_curvature", "rad/m"},
      {"rest_length", "m"},
      {"rest_twist", "rad/m"},
      {"roll", "rad"},
      {"scale", "1"},  // a factor on a file's coordinates, with its "units"
      {"sharpness", "1/m"},
      {"skeleton", "m"},
      {"spacing", "m"},
      {"stabilization", "1/s"},  // Baumgarte's rate ω: g̈ = −2ω ġ − ω² g
      {"stiffness_coefficient", "s"},  // Rayleigh's β: Q = β K q̇
      {"stretch_stiffness", "N/m"},
      {"target", "m"},  // a point; or a body and an abscissa (1)
      {"tensile_strength", "Pa"},
      {"torque", "N·m"},
      {"translation", "m"},
      {"velocities", "m/s"},
      {"xray_opacity", "1"},  // the fraction of X-rays one layer stops
      {"youngs_modulus", "Pa"},
  };
  const auto it = units.find(key);
  return it == units.end() ? "" : it->second;
}

}  // namespace filum
