// Shared by the scene benchmarks: step a scene, turning a failed step into a skipped benchmark
// (a diverged scene must not be timed as if it had run), and time whole simulated intervals.
#pragma once

#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "filum/all_components.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"

namespace filum::bench {

/// The scene of `document` with every component of this build; null after
/// state.SkipWithError(why) when it does not load.
inline std::unique_ptr<Scene> loadOrSkip(const nlohmann::json& document, const std::string& name,
                                         benchmark::State& state) {
  try {
    return loadScene(document, name, app::makeFactory());
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return nullptr;
  }
}

/// Steps `steps` times; on a failed step: state.SkipWithError(prefix + its message), false.
inline bool stepOrSkip(Scene& scene, long steps, benchmark::State& state, const std::string& prefix = "") {
  for (long k = 0; k < steps; ++k) {
    const StepReport report = scene.step();
    if (!report.ok) {
      state.SkipWithError((prefix + report.message).c_str());
      return false;
    }
  }
  return true;
}

/// `warmup_steps` untimed, then `steps_per_iteration` steps per benchmark iteration.
inline void timeSteps(Scene& scene, long warmup_steps, long steps_per_iteration, benchmark::State& state) {
  if (!stepOrSkip(scene, warmup_steps, state, "warm-up: ")) return;
  for (auto _ : state) {
    if (!stepOrSkip(scene, steps_per_iteration, state)) break;
    benchmark::DoNotOptimize(scene.state().q.data());
    benchmark::ClobberMemory();
  }
}

}  // namespace filum::bench
