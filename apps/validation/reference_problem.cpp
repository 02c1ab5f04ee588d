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
  bool out_of_time = false;
  return advance(scene, t_end, std::chrono::steady_clock::time_point::max(), failure, &out_of_time);
}

bool advance(Scene& scene, double t_end, std::chrono::steady_clock::time_point deadline, std::string* failure,
             bool* out_of_time) {
  const double dt = scene.settings().dt;
  *out_of_time = false;
  while (scene.state().time < t_end - 0.5 * dt) {
    const StepReport report = scene.step();
    if (!report.ok) {
      if (failure) *failure = report.message;
      return false;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      *out_of_time = true;
      if (failure) *failure = "over the wall-time budget";
      return false;
    }
  }
  return true;
}

RunResult runProblem(const ReferenceProblem& problem, const RunSettings& settings) {
  auto scene = loadProblem(problem, settings);
  RunResult result;
  using Clock = std::chrono::steady_clock;
  const auto deadline = settings.wall_budget > 0.0
                            ? Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                 std::chrono::duration<double>(settings.wall_budget))
                            : Clock::time_point::max();
  double wall = 0.0;
  for (double t : problem.sampleTimes()) {
    const auto start = Clock::now();
    const bool ok = advance(*scene, t, deadline, &result.failure, &result.over_budget);
    wall += std::chrono::duration<double>(Clock::now() - start).count();
    result.simulated = scene->state().time;
    if (!ok) {
      result.stable = result.over_budget;  // too slow is not unstable
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
  if (!result.stable || result.over_budget) result.error = std::numeric_limits<double>::infinity();
  return result;
}

}  // namespace filum::validation
