#include "filum/physics_check.hpp"

#include <cmath>
#include <sstream>

#include <Eigen/SparseCholesky>

#include "filum/core/curve_body.hpp"
#include "filum/core/jacobian_accumulator.hpp"

namespace filum::app {

namespace {

std::string number(double x) {
  std::ostringstream out;
  out.precision(3);
  out << x;
  return out.str();
}

/// ω dt on the imaginary axis below which the explicit scheme is stable; 0: not checked.
double stabilityLimit(const std::string& integrator) {
  if (integrator == "RungeKutta4") return 2.0 * std::sqrt(2.0);
  if (integrator == "SymplecticEuler") return 2.0;
  return 0.0;
}

}  // namespace

double stiffestFrequency(const Scene& scene) {
  // Up to 20,000 points (200 sparse solves of a band of 60,000 unknowns: a fraction of a second);
  // beyond, and for bodies with internal DOFs, not estimated.
  if (scene.hasInternalDofs() || scene.dofPointCount() == 0 || scene.dofPointCount() > 20000) return 0.0;
  for (const ForceField* f : scene.forceFields())
    if (!f->hasJacobian()) return 0.0;
  const int n = 3 * scene.stepGroupCount();
  Triplets kt, mt;
  TripletAccumulator k_accumulator(kt), m_accumulator(mt);
  scene.addForceJacobian(scene.state(), -1.0, 0.0, k_accumulator);  // −K
  scene.addMassMatrix(1.0, m_accumulator);
  SparseMatrix K(n, n), M(n, n);
  K.setFromTriplets(kt.begin(), kt.end());
  M.setFromTriplets(mt.begin(), mt.end());
  const Eigen::SimplicialLDLT<SparseMatrix> mass(M);
  if (mass.info() != Eigen::Success) return 0.0;
  // Power iteration on M⁻¹(−K) from a fixed alternating start (rich in the stiff, short-wave
  // modes); the Rayleigh quotient xᵀ(−K)x / xᵀMx after 200 iterations.
  VecX x(n);
  for (int i = 0; i < n; ++i) x[i] = (i % 2 ? 1.0 : -1.0) * (1.0 + 0.1 * std::sin(1.3 * i));
  double lambda = 0.0;
  for (int it = 0; it < 200; ++it) {
    const VecX y = mass.solve(K * x);
    const double norm = y.norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) return 0.0;
    x = y / norm;
    lambda = x.dot(K * x) / x.dot(M * x);
  }
  return std::sqrt(std::abs(lambda));
}

std::vector<std::string> physicsProblems(const Scene& scene, const nlohmann::json& document) {
  std::vector<std::string> problems;
  const std::string& source = scene.settings().source;
  // Slender bodies only: the length of the curve sampled at 200 abscissas.
  for (const MechanicalState* body : scene.bodies()) {
    const CurveBody* curve = body->curve();
    if (!curve) continue;
    double length = 0.0;
    Vec3 previous = curve->position(scene.state().q, 0.0);
    for (int k = 1; k <= 200; ++k) {
      const Vec3 x = curve->position(scene.state().q, k / 200.0);
      length += (x - previous).norm();
      previous = x;
    }
    const double radius = curve->radius();
    if (radius > 0.5 * length) {
      std::string message = body->origin();
      message += "/radius: expected a radius below half the body's length (";
      message += number(length);
      message += " m: a thread is slender; radii are in metres, 1e-4 is a 3-0 suture), found ";
      message += number(radius);
      message += " m";
      problems.push_back(message);
    }
  }
  // Explicit steps within their stability limit.
  const std::string integrator = scene.integrator().typeName();
  const double limit = stabilityLimit(integrator);
  if (limit > 0.0) {
    const double omega = stiffestFrequency(scene), dt = scene.settings().dt;
    if (omega * dt > 1.5 * limit) {
      const bool defaulted = !document.is_object() || !document.contains("integrator");
      std::string message = source;
      message += ": /dt: expected a step within ";
      message += integrator;
      message += "'s stability limit, dt <= " + number(limit / omega);
      message += " s (omega dt <= " + number(limit);
      message += "; the scene's stiffest mode has omega = " + number(omega);
      message += " rad/s at the start)";
      if (defaulted) message += ", since the scene names no \"integrator\" and runs the default " + integrator;
      message += ", or an implicit integrator (\"integrator\": {\"type\": \"ImplicitEuler\"}), stable at any step; found dt = ";
      message += number(dt);
      message += " s";
      problems.push_back(message);
    }
  }
  return problems;
}

}  // namespace filum::app
