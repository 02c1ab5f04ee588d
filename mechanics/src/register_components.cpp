#include "filum/mechanics/register_components.hpp"

#include "filum/mechanics/adaptive_refinement.hpp"
#include "filum/mechanics/chain_elasticity.hpp"
#include "filum/mechanics/curvature_bending.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/mechanics/explicit_euler.hpp"
#include "filum/mechanics/framed_chain.hpp"
#include "filum/mechanics/global_stretching.hpp"
#include "filum/mechanics/green_lagrange_stretching.hpp"
#include "filum/mechanics/implicit_euler.hpp"
#include "filum/mechanics/implicit_midpoint.hpp"
#include "filum/mechanics/parametric_bending.hpp"
#include "filum/mechanics/point_load.hpp"
#include "filum/mechanics/rayleigh_damping.hpp"
#include "filum/mechanics/rod_end_frame.hpp"
#include "filum/mechanics/runge_kutta4.hpp"
#include "filum/mechanics/spring_force_field.hpp"
#include "filum/mechanics/symplectic_euler.hpp"
#include "filum/mechanics/tissue_attachment.hpp"
#include "filum/mechanics/viscous_damping.hpp"

namespace filum::mechanics {

void register_components(Factory& factory) {
  factory.add("DynamicSpline", "dynamic Lagrangian spline: control points as DOFs, banded mass (paper §3)",
              [](const Params& p) { return DynamicSpline::fromParams(p); });
  factory.add("FramedChain", "a discrete Cosserat rod: point masses with a material frame per segment (catheters, guidewires)",
              [](const Params& p) { return FramedChain::fromParams(p); });

  factory.add("AdaptiveRefinement",
              "adaptive NUBS at run time: control points inserted where the curve bends or is touched, removed where it is straight",
              [](const Params& p) { return AdaptiveRefinement::fromParams(p); });

  // Energies and dissipation (each with an analytic Jacobian, for the implicit integrators).
  factory.add("SpringForceField", "stretch and bend springs between points sampled on the curve (paper Fig. 1)",
              [](const Params& p) { return SpringForceField::fromParams(p); });
  factory.add("GreenLagrangeStretching",
              "continuous stretching 1/2 EA int eps^2 dsigma, Green-Lagrange strain (Nocent et al. 2001)",
              [](const Params& p) { return GreenLagrangeStretching::fromParams(p); });
  factory.add("GlobalStretching", "the paper's global stretching 1/2 k (l^2/l0^2 - 1)^2, k = EA l0/4 (§3)",
              [](const Params& p) { return GlobalStretching::fromParams(p); });
  factory.add("ParametricBending", "quadratic bending 1/2 EI int |P''|^2 dsigma, constant banded stiffness",
              [](const Params& p) { return ParametricBending::fromParams(p); });
  factory.add("CurvatureBending", "exact bending 1/2 EI int kappa^2 dl",
              [](const Params& p) { return CurvatureBending::fromParams(p); });
  factory.add("ChainElasticity", "stretching, shear, bending and twist of a FramedChain (discrete Cosserat rod)",
              [](const Params& p) { return ChainElasticity::fromParams(p); });
  factory.add("RodEndFrame", "holds an end's material frame of a FramedChain (built-in end: direction and roll)",
              [](const Params& p) { return RodEndFrame::fromParams(p); });
  factory.add("PointLoad", "a force (any curve) and a torque (rods with frames) at an abscissa, constant or on a path",
              [](const Params& p) { return PointLoad::fromParams(p); });
  factory.add("TissueAttachment",
              "springs and dashpots from points of a curve to anchors: mesosalpinx, mesentery, ligament",
              [](const Params& p) { return TissueAttachment::fromParams(p); });
  factory.add("ViscousDamping", "mass-proportional viscous drag Q = -gamma M v",
              [](const Params& p) { return ViscousDamping::fromParams(p); });
  factory.add("RayleighDamping", "stiffness-proportional damping Q = beta K(q) v",
              [](const Params& p) { return RayleighDamping::fromParams(p); });

  // Integrators.
  factory.add("ExplicitEuler", "forward Euler, first order (baseline)",
              [](const Params& p) { return ExplicitEuler::fromParams(p); });
  factory.add("SymplecticEuler", "semi-implicit Euler, first order, symplectic",
              [](const Params& p) { return SymplecticEuler::fromParams(p); });
  factory.add("RungeKutta4", "classical fourth-order Runge-Kutta (paper §3)",
              [](const Params& p) { return RungeKutta4::fromParams(p); });
  factory.add("ImplicitEuler", "backward Euler, Newton on the analytic Jacobian, first order, L-stable",
              [](const Params& p) { return ImplicitEuler::fromParams(p); });
  factory.add("ImplicitMidpoint", "implicit midpoint, Newton on the analytic Jacobian, second order, symplectic",
              [](const Params& p) { return ImplicitMidpoint::fromParams(p); });
  factory.setDefault("Integrator", "RungeKutta4");
}

}  // namespace filum::mechanics
