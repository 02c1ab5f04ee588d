#include "filum/constraints/register_components.hpp"

#include "filum/constraints/channel_constraint.hpp"
#include "filum/constraints/clamp_constraint.hpp"
#include "filum/constraints/fixed_point_constraint.hpp"
#include "filum/constraints/lagrange_multiplier_solver.hpp"
#include "filum/constraints/point_on_axis_constraint.hpp"
#include "filum/constraints/point_on_plane_constraint.hpp"
#include "filum/constraints/sliding_point_constraint.hpp"
#include "filum/constraints/spline_junction_constraint.hpp"

namespace filum::constraints {

void register_components(Factory& factory) {
  factory.add("FixedPointConstraint",
              "holds the curve point at an abscissa on a fixed, scripted or attached target (3 rows)",
              [](const Params& p) { return FixedPointConstraint::fromParams(p); });
  factory.add("PointOnAxisConstraint", "keeps the curve point at an abscissa on a line (2 rows, paper Fig. 1a)",
              [](const Params& p) { return PointOnAxisConstraint::fromParams(p); });
  factory.add("PointOnPlaneConstraint", "keeps the curve point at an abscissa on a plane (1 row, paper Fig. 1a)",
              [](const Params& p) { return PointOnPlaneConstraint::fromParams(p); });
  factory.add("ClampConstraint", "holds the curve point and its tangent direction: a clamp, a cantilever (5 rows)",
              [](const Params& p) { return ClampConstraint::fromParams(p); });
  factory.add("ChannelConstraint",
              "keeps the body on a fixed channel's centre line while it is inside (a coil in a microcatheter; "
              "2 rows per point inside)",
              [](const Params& p) { return ChannelConstraint::fromParams(p); });
  factory.add("SlidingPointConstraint",
              "the thread passes through a point and slides through it, s(t) free (2 rows + 1 DOF, suture)",
              [](const Params& p) { return SlidingPointConstraint::fromParams(p); });
  factory.add("SplineJunctionConstraint", "joins two splines with C0, C1 or C2 continuity (3, 6 or 9 rows)",
              [](const Params& p) { return SplineJunctionConstraint::fromParams(p); });
  factory.add("LagrangeMultiplierSolver",
              "bilateral constraints by Lagrange multipliers (paper §4); contacts with Coulomb friction by "
              "semismooth Newton",
              [](const Params& p) { return LagrangeMultiplierSolver::fromParams(p); });
  factory.setDefault("ConstraintSolver", "LagrangeMultiplierSolver");
}

}  // namespace filum::constraints
