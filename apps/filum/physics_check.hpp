// Physics mistakes `filum check` refuses before anything runs: what loads and is
// well-formed but cannot run as written.
//  - An explicit integrator whose step exceeds its stability limit: the stiffest mode of the
//    scene, ω_max² the largest eigenvalue of M⁻¹(−K) at the start (K the force fields' own
//    Jacobian, M the mass matrix; by power iteration with the Rayleigh quotient, which
//    approaches ω_max² from below), against ω dt <= 2√2 for RungeKutta4 and 2 for
//    SymplecticEuler on the imaginary axis (measured: apps/bench/results/issue4/stability_map.csv);
//    refused only beyond 1.5 times the limit (the estimate's own error and the damping's margin).
//    A scene without "integrator" runs RungeKutta4: the message says so.
//  - A curve body thicker than it is long (radius > half its length): a 1D model of a slender
//    body cannot hold it, and it is most often a radius in mm written as metres.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "filum/core/scene.hpp"

namespace filum::app {

/// The physics mistakes of a loaded scene, each a message naming the place ("file: /dt: ...");
/// empty when there is none.
std::vector<std::string> physicsProblems(const Scene& scene, const nlohmann::json& document);

/// What a user needs to see a unit mistake at a glance: per curve body its length, radius and mass,
/// then the stiffest mode's period against dt and the integrator (one line each).
std::vector<std::string> scaleSummary(const Scene& scene);

/// For a run that failed in its first steps: the likely causes (dt against the stiffest mode and the
/// integrator's limit, units), naming `filum check` for the scales.
std::string earlyFailureHint(const Scene& scene);

/// ω_max (rad/s) of the scene at its start state: power iteration on M⁻¹(−K); 0 when the scene
/// has no stiffness Jacobian, internal DOFs, or more than 20,000 points (not estimated).
double stiffestFrequency(const Scene& scene);

}  // namespace filum::app
