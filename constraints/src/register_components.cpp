#include "filum/constraints/register_components.hpp"

#include "filum/constraints/fixed_point_constraint.hpp"
#include "filum/constraints/lagrange_multiplier_solver.hpp"

namespace filum::constraints {

void register_components(Factory& factory) {
  factory.add("FixedPointConstraint", "holds the curve point at an abscissa on a fixed or scripted target (3 rows)",
              [](const Params& p) { return FixedPointConstraint::fromParams(p); });
  factory.add("LagrangeMultiplierSolver", "bilateral constraints by Lagrange multipliers (paper §4)",
              [](const Params& p) { return LagrangeMultiplierSolver::fromParams(p); });
  factory.setDefault("ConstraintSolver", "LagrangeMultiplierSolver");
}

}  // namespace filum::constraints
