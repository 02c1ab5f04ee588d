// bench_collision: the cost of collision handling.
//
//  - BroadPhase/<n>: one UniformGridBroadPhase::findPairs over the n chord bounding spheres of
//    threads made of n spheres (radius 1 mm, 1 mm apart, as SphereCollisionModel places them),
//    laid out as random walks (turning by up to 30° per sphere, 100 spheres per thread) in a cube
//    whose side grows like n^(1/3), so that the density — the number of neighbours per sphere —
//    stays the same from 10^3 to 10^5 spheres. Linear time means ns_per_sphere stays constant.
//    BruteForce/1000 tests all n(n − 1)/2 pairs, for scale.
//  - Scene/knot, Scene/threads: wall time per simulated millisecond of apps/scenes/paper_knot.json
//    (paper Fig. 1b: 5.7 ms on a 1.7 GHz Pentium 4) and apps/scenes/paper_threads.json (Fig. 1c:
//    16 ms). One iteration = the steps of one simulated ms, the whole pipeline (detection,
//    contacts, constraints, RK4), no output; a fixed number of iterations from the scene's start
//    (knot: the first 2 s, in which its weight tightens it; threads: the first 1 s, in which the
//    threads swing through each other), so that every repetition times the same motion.
//    Scene/organ (with CGAL): the first 1 s of apps/scenes/paper_organ.json, a thread falling on
//    the triangle-mesh organ (no figure in the paper). Scene/threads_real, Scene/organ_real: the
//    first 1 s of the same scenes in real material (threads.json, organ.json: silicone vessel
//    loops under implicit steps at 1 ms with unilateral contacts).
//    Counters: wall_ms_per_sim_ms, contacts (mean per step), spheres.
// Run: build/apps/bench/bench_collision --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "filum/all_components.hpp"
#include "filum/collision/contact_pipeline.hpp"
#include "filum/collision/uniform_grid_broad_phase.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"

namespace {

using filum::Vec3;
using filum::collision::BoundingSphere;

/// Chord bounding spheres of n spheres on random-walk threads, constant density.
std::vector<BoundingSphere> threadChords(int n) {
  const double r = 1e-3, spacing = 1e-3;
  const int per_thread = 100;
  // 10^3 spheres in a 4 cm cube (besides its neighbours along the thread, a chord meets about
  // one other); the volume grows with n.
  const double side = 0.04 * std::cbrt(n / 1000.0);
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<BoundingSphere> chords;
  Vec3 x = Vec3::Zero(), direction = Vec3::UnitX();
  for (int k = 0; k < n; ++k) {
    if (k % per_thread == 0) {
      x = side * Vec3(u(rng), u(rng), u(rng));
      direction = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
    }
    Vec3 turn = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
    direction = (direction + 0.5 * turn).normalized();
    const Vec3 next = x + spacing * direction;
    // Reflect at the walls of the cube.
    for (int a = 0; a < 3; ++a)
      if (next[a] < 0.0 || next[a] > side) direction[a] = -direction[a];
    const Vec3 end = x + spacing * direction;
    if ((k + 1) % per_thread != 0) chords.push_back({0.5 * (x + end), 0.5 * spacing + r + 0.25e-3});
    x = end;
  }
  return chords;
}

void BroadPhase(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto chords = threadChords(n);
  filum::collision::UniformGridBroadPhase grid;
  std::vector<filum::collision::IndexPair> pairs;
  for (auto _ : state) {
    grid.findPairs(chords, pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  state.counters["spheres"] = n;
  state.counters["pairs"] = static_cast<double>(pairs.size());
  // Wall time per iteration / n, in ns: time / (iterations · n · 1e-9).
  state.counters["ns_per_sphere"] =
      benchmark::Counter(n * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BroadPhase)->Arg(1000)->Arg(3162)->Arg(10000)->Arg(31623)->Arg(100000)->Unit(benchmark::kMicrosecond)->UseRealTime();

void BruteForce(benchmark::State& state) {
  const auto chords = threadChords(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(filum::collision::bruteForcePairs(chords).size());
}
BENCHMARK(BruteForce)->Arg(1000)->Unit(benchmark::kMicrosecond)->UseRealTime();

void Scene(benchmark::State& state, const std::string& file) {
  const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/" + file;
  auto scene = filum::loadScene(path, filum::app::makeFactory());
  const long steps_per_ms = std::lround(1e-3 / scene->settings().dt);
  const auto& pipeline = dynamic_cast<const filum::collision::ContactPipeline&>(*scene->collisionPipeline());
  double contacts = 0.0, spheres = 0.0;
  long steps = 0;
  for (auto _ : state) {
    for (long k = 0; k < steps_per_ms; ++k) {
      const filum::StepReport report = scene->step();
      if (!report.ok) {
        state.SkipWithError(report.message.c_str());  // the benchmark loop ends at its next check
        break;
      }
      contacts += static_cast<double>(pipeline.contacts().size());
      spheres += pipeline.statistics().spheres;
      ++steps;
    }
  }
  // Wall time per iteration (one simulated ms), in ms: time / (iterations · 1e-3).
  state.counters["wall_ms_per_sim_ms"] =
      benchmark::Counter(1e-3, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["contacts"] = contacts / std::max(steps, 1L);
  state.counters["spheres"] = spheres / std::max(steps, 1L);
}
BENCHMARK_CAPTURE(Scene, knot, std::string("paper_knot.json"))->Iterations(2000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(Scene, threads, std::string("paper_threads.json"))->Iterations(1000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(Scene, threads_real, std::string("threads.json"))->Iterations(1000)->Unit(benchmark::kMillisecond)->UseRealTime();
#ifdef FILUM_WITH_CGAL
BENCHMARK_CAPTURE(Scene, organ, std::string("paper_organ.json"))->Iterations(1000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(Scene, organ_real, std::string("organ.json"))->Iterations(1000)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif

}  // namespace
