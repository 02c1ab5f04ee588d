#include "filum/physics_check.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include <Eigen/SparseCholesky>

#include "filum/core/curve_body.hpp"
#include "filum/core/jacobian_accumulator.hpp"
#include "filum/core/node.hpp"

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

double curveLength(const CurveBody& curve, const SceneState& s) {
  // The polyline through 201 points of the curve: within (κ Δs)² / 24 of the arc length.
  double length = 0.0;
  Vec3 previous = curve.position(s.q, 0.0);
  for (int k = 1; k <= 200; ++k) {
    const Vec3 x = curve.position(s.q, k / 200.0);
    length += (x - previous).norm();
    previous = x;
  }
  return length;
}

std::vector<std::string> scaleSummary(const Scene& scene) {
  std::vector<std::string> lines;
  for (const MechanicalState* body : scene.bodies()) {
    const CurveBody* curve = body->curve();
    if (!curve) continue;
    const std::string name = body->node() && !body->node()->path().empty() ? body->node()->path() : body->name();
    lines.push_back(name + " (" + body->typeName() + "): length " + number(curveLength(*curve, scene.state())) +
                    " m, radius " + number(curve->radius()) + " m, mass " + number(curve->mass()) + " kg");
  }
  const double omega = stiffestFrequency(scene), dt = scene.settings().dt;
  const std::string integrator = scene.integrator().typeName();
  if (omega > 0.0)
    lines.push_back("stiffest mode: period 2 pi / omega = " + number(2.0 * std::numbers::pi / omega) + " s (omega dt = " +
                    number(omega * dt) + " at dt = " + number(dt) + " s, " + integrator + ")");
  else
    lines.push_back("dt = " + number(dt) + " s, " + integrator);
  return lines;
}

std::string earlyFailureHint(const Scene& scene) {
  const double omega = stiffestFrequency(scene), dt = scene.settings().dt;
  const std::string integrator = scene.integrator().typeName();
  std::string hint = "likely cause: a run that fails in its first steps is most often set up wrong, not broken in "
                     "the component that noticed: the step (dt = " + number(dt) + " s, " + integrator + ")";
  if (omega > 0.0 && std::isfinite(omega)) {
    hint += " against the scene's stiffest mode, period " + number(2.0 * std::numbers::pi / omega) + " s (omega dt = " +
            number(omega * dt);
    const double limit = stabilityLimit(integrator);
    if (limit > 0.0) hint += "; " + integrator + " is stable up to " + number(limit);
    hint += ")";
  }
  hint += ", or a quantity in the wrong units (radii, lengths in m, moduli in Pa, densities in kg/m^3): `filum check " +
          scene.settings().source + "` lists each body's length, radius and mass";
  return hint;
}

std::vector<std::string> physicsProblems(const Scene& scene, const nlohmann::json& document) {
  std::vector<std::string> problems;
  const std::string& source = scene.settings().source;
  // Slender bodies only: a radius below half the length.
  for (const MechanicalState* body : scene.bodies()) {
    const CurveBody* curve = body->curve();
    if (!curve) continue;
    const double length = curveLength(*curve, scene.state());
    const double radius = curve->radiusRange().largest;  // its thickest section (a rod's spans)
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
