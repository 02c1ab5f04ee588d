// Stability map: the largest stable time step of an integrator as the thread's
// stiffness grows. Problem: a 10 cm thread of 3-0 suture geometry (r = 0.1 mm, ρ = 910 kg/m³)
// with GreenLagrangeStretching and ParametricBending of Young's modulus E, held at one end
// (FixedPointConstraint), released horizontally under gravity, lightly damped (viscous γ = 1/s).
// Its stiffest (axial) mode has ω_max ∝ √E (c = √(E/ρ)), so explicit schemes are stable
// below dt ≈ C / ω_max ∝ E^(−1/2) (C = 2 for symplectic Euler, 2√2 for RK4 on the imaginary
// axis); backward Euler and the implicit midpoint rule are A-stable.
// A run of `steps` steps is unstable when a step fails (non-finite state, a point faster than the
// scene's max_speed, Newton failing even after halving) or when the total energy rises above
// its start by more than 5 % of m g L (the energy the swing exchanges): an undamped thread can
// only lose energy.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "filum/core/scene.hpp"

namespace filum::validation {

struct StabilityProblem {
  double youngs_modulus = 2e9;  // E (Pa)
  int control_points = 20;
  int steps = 2000;             // steps per trial run
  double damping = 1.0;         // viscous γ (1/s)
};

/// Runs `problem.steps` steps of dt; false (with the reason) when the run is unstable.
bool runIsStable(const nlohmann::json& integrator, const StabilityProblem& problem, double dt, std::string* why = nullptr);

/// ω_max (rad/s) of the problem's linearized dynamics at its start (generalized eigenvalues of
/// −K v = λ M v, K the analytic Jacobian; the fixed point is left out: it removes modes, it does
/// not stiffen them).
double stiffestFrequency(const StabilityProblem& problem);

/// ω_max (rad/s) of a scene's linearized dynamics at state s: the largest |λ| of −K v = λ M v
/// (K the symmetric part of the analytic Jacobian ∂Q/∂q, M the mass matrix), square-rooted.
/// Dense generalized eigenproblem: for test-sized scenes.
double stiffestFrequency(const Scene& scene, const SceneState& s);

/// The largest dt in [dt_min, dt_max] for which the run is stable, by bisection on log dt
/// (`bisections` halvings of the bracket); dt_max if stable there, 0 if dt_min is unstable.
/// Assumes stability is monotone in dt.
double largestStableStep(const nlohmann::json& integrator, const StabilityProblem& problem, double dt_min, double dt_max,
                         int bisections);

}  // namespace filum::validation
