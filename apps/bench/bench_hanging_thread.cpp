// bench_hanging_thread: wall-clock time per simulated millisecond of the soft-spring thread,
// apps/scenes/paper_hanging_thread.json (explicit RK4, springs, viscous damping, one fixed point by
// Lagrange multipliers), for n = 30 control points (the file as it is) and n = 165. Why: the
// paper's claim is real time for a suture thread; real time means wall_ms_per_sim_ms <= 1.
//
// One benchmark iteration = the steps of one simulated millisecond (Scene::step, the whole
// pipeline, no output). The scene is loaded once per run with filum::readJsonFile, patched
// (nodes[0].components[0].control_points.count, and for one variant dt and the springs), and
// built with filum::loadScene(document, name, filum::app::makeFactory()); 20 simulated ms are
// stepped untimed first. Every StepReport is checked: a divergence fails the benchmark
// (SkipWithError). Real (wall) time, not CPU time, is what the counters use.
//
// Counters: wall_ms_per_sim_ms (the headline), us_per_step, dt_us (the time step used),
// control_points.
//
// The time step at n = 165. RK4 is stable while ω_max dt < 2.8 (ω_max: stiffest mode). The
// file's springs have a fixed stiffness per spring (k = 1 N/m); the default sampling puts
// 2n points on the curve, so ω_max grows like √n with that model. Measured with `filum run`
// on patched copies of the scene (0.3 s, bisection on dt): n = 30 diverges above dt ≈ 2.7e-4 s
// (ω_max ≈ 1.0e4 rad/s, ω dt ≈ 1.0 at the file's dt = 1e-4); n = 165 diverges above
// dt ≈ 1.05e-4 s, so the file's dt = 1e-4 is still stable (2 s run checked) but only with a
// 5 % margin (ω dt ≈ 2.7). Two n = 165 variants are therefore measured:
//   - n165_fileSprings:  the file as it is, only the count patched, dt = 1e-4 s;
//   - n165_constantEA:   the same physical thread refined: a spring of rest length l stands
//     for an axial stiffness EA with k = EA / l, so keeping the thread (EA, and likewise the
//     bend springs and the dashpots c = η A / l) while going from 2·30 − 1 to 2·165 − 1 springs
//     multiplies stretch_stiffness, bend_stiffness and damping by 329/59 ≈ 5.58. ω_max then grows
//     like n (measured divergence above dt ≈ 4.2e-5 s), so dt is divided by the same factor:
//     56 steps per simulated ms, dt ≈ 1.79e-5 s, ω dt ≈ 1.2 as the scene file's comment asks.
// Cost per step is the same for both n = 165 variants; only the steps per simulated ms differ.
#include <cmath>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "filum/all_components.hpp"
#include "scene_stepping.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"

namespace {

struct Variant {
  int control_points;
  bool constant_ea;  // false: the file's per-spring constants; true: EA kept, dt scaled
};

constexpr int kFileControlPoints = 30;     // control_points.count in the scene file
constexpr int kWarmupSimulatedMs = 20;

/// Number of springs of one family with the default sampling (2n samples): 2n − 1.
double springCount(int control_points) { return 2.0 * control_points - 1.0; }

/// Returns the first component of `type` in `components`, or nullptr.
nlohmann::json* findComponent(nlohmann::json& components, const std::string& type) {
  for (auto& c : components)
    if (c.value("type", "") == type) return &c;
  return nullptr;
}

void hangingThread(benchmark::State& state, Variant variant) {
  const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/paper_hanging_thread.json";
  nlohmann::json document = filum::readJsonFile(path);
  nlohmann::json& thread = document["nodes"][0]["components"];
  thread[0]["control_points"]["count"] = variant.control_points;

  double dt = document.value("dt", 1e-4);
  if (variant.constant_ea) {
    nlohmann::json* springs = findComponent(thread, "SpringForceField");
    if (!springs || springs->contains("samples")) {
      state.SkipWithError("scene changed: expected a SpringForceField with default sampling");
      return;
    }
    const double scale = springCount(variant.control_points) / springCount(kFileControlPoints);
    for (const char* key : {"stretch_stiffness", "bend_stiffness", "damping"})
      (*springs)[key] = springs->value(key, 0.0) * scale;
    // Integer steps per simulated ms, dt no larger than the file's dt / scale.
    dt = 1e-3 / std::ceil(1e-3 / dt * scale);
    document["dt"] = dt;
  }
  const long steps_per_ms = std::lround(1e-3 / dt);

  std::unique_ptr<filum::Scene> scene = filum::bench::loadOrSkip(document, path + " (patched)", state);
  if (!scene) return;

  filum::bench::timeSteps(*scene, kWarmupSimulatedMs * steps_per_ms, steps_per_ms, state);

  using benchmark::Counter;
  state.counters["wall_ms_per_sim_ms"] = Counter(1e-3, Counter::kIsIterationInvariantRate | Counter::kInvert);
  state.counters["us_per_step"] =
      Counter(1e-6 * static_cast<double>(steps_per_ms), Counter::kIsIterationInvariantRate | Counter::kInvert);
  state.counters["dt_us"] = dt * 1e6;
  state.counters["control_points"] = variant.control_points;
}

}  // namespace

BENCHMARK_CAPTURE(hangingThread, n30_file, Variant{30, false})->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(hangingThread, n165_fileSprings, Variant{165, false})->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(hangingThread, n165_constantEA, Variant{165, true})->UseRealTime()->Unit(benchmark::kMicrosecond);
