// Reference problems with analytic solutions (validation against analytic physics):
// a scene builder, the analytic solution and an error measure, shared by the tests
// (tests/mechanics/*_validation_test.cpp) and the run-time-against-error benchmark
// (apps/bench/accuracy_pareto.cpp). Scenes are JSON documents loaded by the same path as scene
// files, so the problems exercise exactly what `filum run` runs.
#pragma once

#include <chrono>

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "filum/core/scene.hpp"

namespace filum::validation {

/// A round thread in SI units; the defaults are a 3-0 polypropylene suture.
struct Material {
  double youngs_modulus = 2.0e9;  // E (Pa)
  double radius = 1.0e-4;         // r (m)
  double density = 910.0;         // ρ (kg/m³)

  double area() const;                 // A = π r² (m²)
  double secondMoment() const;         // I = π r⁴ / 4 (m⁴)
  double linearDensity() const;        // μ = ρ A (kg/m)
  double axialStiffness() const { return youngs_modulus * area(); }          // E A (N)
  double bendingStiffness() const { return youngs_modulus * secondMoment(); }  // E I (N·m²)
};

/// How a problem is run: the integrator (a scene-file object with "type"), the step and the
/// number of control points.
struct RunSettings {
  nlohmann::json integrator = {{"type", "ImplicitEuler"}};
  double dt = 1e-4;        // s
  int control_points = 30;
  double wall_budget = 0.0;  // s of wall time for the whole run; 0: no limit
};

class ReferenceProblem {
 public:
  virtual ~ReferenceProblem() = default;
  virtual std::string name() const = 0;
  /// What error() measures, with its unit, for reports.
  virtual std::string errorMeaning() const = 0;
  /// The scene for these settings.
  virtual nlohmann::json scene(const RunSettings& settings) const = 0;
  /// Sets the initial state after loading (default: the scene's own).
  virtual void prepare(Scene& /*scene*/) const {}
  /// Simulated time of a run (s).
  virtual double duration() const = 0;
  /// Times at which error() is evaluated; the run's error is the largest (s).
  virtual std::vector<double> sampleTimes() const { return {duration()}; }
  /// Error of the current state against the analytic solution at the state's time.
  virtual double error(const Scene& scene) const = 0;
};

struct RunResult {
  bool stable = true;          // no step failed and the error stayed finite
  std::string failure;         // the first failed step's message
  double error = 0.0;          // max of error() over the sample times (inf if unstable)
  double wall_seconds = 0.0;   // wall time of the stepping only (s)
  double simulated = 0.0;      // simulated time reached (s)
  long steps = 0;
  bool over_budget = false;    // stopped after RunSettings::wall_budget (error inf, not unstable)
  double wallPerSimulatedSecond() const { return simulated > 0.0 ? wall_seconds / simulated : 0.0; }
};

/// Loads, prepares and runs the problem; measures the error at its sample times. Scene errors
/// (SceneError) propagate.
RunResult runProblem(const ReferenceProblem& problem, const RunSettings& settings);

/// Loads the problem's scene (and prepares its state) without running it.
std::unique_ptr<Scene> loadProblem(const ReferenceProblem& problem, const RunSettings& settings);

/// Steps until scene time >= t_end (to within dt/2); false at the first failed step.
bool advance(Scene& scene, double t_end, std::string* failure = nullptr);
/// The same, giving up (false, `*out_of_time` set) once steady_clock passes `deadline`.
bool advance(Scene& scene, double t_end, std::chrono::steady_clock::time_point deadline, std::string* failure,
             bool* out_of_time);

/// A node with one DynamicSpline holding the given control points and mass.
nlohmann::json splineComponent(const nlohmann::json& control_points, double mass, double radius);

}  // namespace filum::validation
