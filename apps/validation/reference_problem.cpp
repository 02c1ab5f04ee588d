#include "validation/reference_problem.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "filum/all_components.hpp"
#include "filum/core/scene_loader.hpp"

namespace filum::validation {

double Material::area() const { return std::numbers::pi * radius * radius; }
double Material::secondMoment() const { return 0.25 * std::numbers::pi * std::pow(radius, 4); }
double Material::linearDensity() const { return density * area(); }

nlohmann::json splineComponent(const nlohmann::json& control_points, double mass, double radius) {
  return {{"type", "DynamicSpline"}, {"control_points", control_points}, {"mass", mass}, {"radius", radius}};
}

std::unique_ptr<Scene> loadProblem(const ReferenceProblem& problem, const RunSettings& settings) {
  static const Factory factory = app::makeFactory();
  auto scene = loadScene(problem.scene(settings), problem.name(), factory);
  problem.prepare(*scene);
  return scene;
}

bool advance(Scene& scene, double t_end, std::string* failure) {
  const double dt = scene.settings().dt;
  while (scene.state().time < t_end - 0.5 * dt) {
    const StepReport report = scene.step();
    if (!report.ok) {
      if (failure) *failure = report.message;
      return false;
    }
  }
  return true;
}

RunResult runProblem(const ReferenceProblem& problem, const RunSettings& settings) {
  auto scene = loadProblem(problem, settings);
  RunResult result;
  using Clock = std::chrono::steady_clock;
  double wall = 0.0;
  for (double t : problem.sampleTimes()) {
    const auto start = Clock::now();
    const bool ok = advance(*scene, t, &result.failure);
    wall += std::chrono::duration<double>(Clock::now() - start).count();
    result.simulated = scene->state().time;
    if (!ok) {
      result.stable = false;
      break;
    }
    const double e = problem.error(*scene);
    if (!std::isfinite(e)) {
      result.stable = false;
      result.failure = "non-finite error";
      break;
    }
    result.error = std::max(result.error, e);
  }
  result.wall_seconds = wall;
  result.steps = scene->stepCount();
  if (!result.stable) result.error = std::numeric_limits<double>::infinity();
  return result;
}

}  // namespace filum::validation
