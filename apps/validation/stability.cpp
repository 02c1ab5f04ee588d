#include "validation/stability.hpp"

#include <cmath>
#include <cstdio>

#include <Eigen/Eigenvalues>

#include "filum/all_components.hpp"
#include "filum/core/scene_loader.hpp"
#include "validation/reference_problem.hpp"

namespace filum::validation {

namespace {

std::unique_ptr<Scene> stabilityScene(const nlohmann::json& integrator, const StabilityProblem& problem, double dt) {
  Material material;
  material.youngs_modulus = problem.youngs_modulus;
  const double length = 0.1, mass = material.linearDensity() * length;
  nlohmann::json components = nlohmann::json::array();
  components.push_back(splineComponent(
      {{"from", {0.0, 0.0, 0.0}}, {"to", {length, 0.0, 0.0}}, {"count", problem.control_points}}, mass, material.radius));
  components.push_back({{"type", "GreenLagrangeStretching"}, {"youngs_modulus", problem.youngs_modulus}});
  components.push_back({{"type", "ParametricBending"}, {"youngs_modulus", problem.youngs_modulus}});
  if (problem.damping > 0.0) components.push_back({{"type", "ViscousDamping"}, {"coefficient", problem.damping}});
  components.push_back({{"type", "FixedPointConstraint"}, {"abscissa", 0.0}});
  const nlohmann::json document = {{"name", "stability"},
                                   {"dt", dt},
                                   // The trial's own length: the default 1 s is 1e9 steps at the
                                   // bracket's dt = 1e-9 s, beyond the loader's kMaxSteps.
                                   {"duration", problem.steps * dt},
                                   {"gravity", {0.0, 0.0, -9.81}},
                                   {"integrator", integrator},
                                   {"nodes", nlohmann::json::array({{{"name", "thread"}, {"components", components}}})}};
  static const Factory factory = app::makeFactory();
  return loadScene(document, "stability", factory);
}

}  // namespace

double stiffestFrequency(const StabilityProblem& problem) {
  auto scene = stabilityScene({{"type", "RungeKutta4"}}, problem, 1e-4);
  return stiffestFrequency(*scene, scene->state());
}

double stiffestFrequency(const Scene& scene, const SceneState& s) {
  Triplets kt, mt;
  TripletAccumulator k_accumulator(kt), m_accumulator(mt);
  scene.addForceJacobian(s, 1.0, 0.0, k_accumulator);
  scene.addMassMatrix(1.0, m_accumulator);
  const Eigen::Index n = s.q.size();
  Eigen::SparseMatrix<double> K(n, n), M(n, n);
  K.setFromTriplets(kt.begin(), kt.end());
  M.setFromTriplets(mt.begin(), mt.end());
  const MatX Kd = MatX(K);
  const VecX eig = Eigen::GeneralizedSelfAdjointEigenSolver<MatX>(-0.5 * (Kd + Kd.transpose()), MatX(M)).eigenvalues();
  return std::sqrt(eig.cwiseAbs().maxCoeff());
}

bool runIsStable(const nlohmann::json& integrator, const StabilityProblem& problem, double dt, std::string* why) {
  auto scene = stabilityScene(integrator, problem, dt);
  const double length = 0.1, mass = Material{}.linearDensity() * length;  // as in stabilityScene
  const double start = scene->energy(scene->state()).total();
  const double bound = start + 0.05 * mass * 9.81 * length;
  for (int k = 0; k < problem.steps; ++k) {
    const StepReport report = scene->step();
    if (!report.ok) {
      if (why) *why = report.message;
      return false;
    }
    const double energy = scene->energy(scene->state()).total();
    if (!(energy <= bound)) {
      if (why) {
        char text[160];
        std::snprintf(text, sizeof text, "step %d: energy rose to %.3e J (start %.3e J, bound %.3e J)", k + 1, energy, start,
                      bound);
        *why = text;
      }
      return false;
    }
  }
  return true;
}

double largestStableStep(const nlohmann::json& integrator, const StabilityProblem& problem, double dt_min, double dt_max,
                         int bisections) {
  if (runIsStable(integrator, problem, dt_max)) return dt_max;
  if (!runIsStable(integrator, problem, dt_min)) return 0.0;
  double lo = std::log(dt_min), hi = std::log(dt_max);  // stable at lo, unstable at hi
  for (int k = 0; k < bisections; ++k) {
    const double mid = 0.5 * (lo + hi);
    (runIsStable(integrator, problem, std::exp(mid)) ? lo : hi) = mid;
  }
  return std::exp(lo);
}

}  // namespace filum::validation
