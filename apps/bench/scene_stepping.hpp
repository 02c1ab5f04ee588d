// Shared by the scene benchmarks: step a scene, turning a failed step into a skipped benchmark
// (a diverged scene must not be timed as if it had run), and time whole simulated intervals.
#pragma once

#include <benchmark/benchmark.h>

#include <string>

#include "filum/core/scene.hpp"

namespace filum::bench {

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
