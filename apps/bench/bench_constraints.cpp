// bench_constraints: cost of bilateral constraints by Lagrange multipliers (paper §4), against
// the slides' table and beyond it.
//
// 1. slides/...: the slides' table — 30 control points + 6 constraint rows, 30 + 9, 50 + 9:
//    4.5, 6.1 and 10.7 ms of computation per simulated ms on a 1.7 GHz Pentium 4 (implicit
//    Euler, springs). Scene: apps/scenes/paper_constraints.json (paper Fig. 1a: fixed point 3 rows,
//    point on axis 2, point on plane 1, probe 3), without the probe for 6 rows, its probe kept
//    on (no "release_at") for 9, its control point count patched to 50 for the last line. We
//    integrate with explicit RK4 (4 force and constraint evaluations per step; the scene's
//    integrator) and with symplectic Euler (1 per step), dt = 1e-4 s: 10 steps per simulated
//    ms. Counters: wall_ms_per_sim_ms (the slides' unit), paper_ms and speedup = paper_ms /
//    wall_ms_per_sim_ms (hardware and compiler included: a 2026 core against a 2004 one).
// 2. scaling/n/c/reuse: a long thread with the same spacing, mass and springs per control point
//    as the scene (3.7 mm, so dt = 1e-4 s stays stable at any n: ω_max does not grow with n),
//    held by c rows — groups {fixed point, point on axis, point on plane} spread evenly, the
//    remainder as one smaller group — under gravity. n up to 5000, c up to 500. reuse = 1 is
//    the default solver (M⁻¹ w kept between calls for anchors at fixed abscissas: the solver's
//    per-step cost is then O(c² + n)); reuse = 0 solves every anchor in every call (O(a·n),
//    a anchors), showing the O(c·n) — but W itself is then still the same matrix bit for bit and
//    its factorization is kept. sliding = 1 replaces the groups by {sliding point 2 rows, point
//    on plane 1}: the holes' abscissas move every step, so every call solves the moved anchors,
//    reassembles W and factors it again (dense LDLᵀ up to 64 rows, CHOLMOD above): the whole
//    O(a·n + c² + factorization) cost of a suture.
// 3. solve/n/c/reuse: LagrangeMultiplierSolver::solve alone on fixed rows (no forces, no
//    integrator): the constraint part of the cost only.
// Every StepReport is checked (a divergence fails the benchmark). Real (wall) time.
//
//   build/apps/bench/bench_constraints --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>

#include "filum/all_components.hpp"
#include "scene_stepping.hpp"
#include "filum/constraints/lagrange_multiplier_solver.hpp"
#include "filum/core/flush_denormals.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"

namespace {

using nlohmann::json;
constexpr int kWarmupSimulatedMs = 20;     // the slides' scenes: past the first transient
constexpr int kScalingWarmupSimulatedMs = 2;  // long threads: the cost per step does not depend on it

void setCounters(benchmark::State& state, long steps_per_ms, const filum::Scene& scene) {
  using benchmark::Counter;
  state.counters["wall_ms_per_sim_ms"] = Counter(1e-3, Counter::kIsIterationInvariantRate | Counter::kInvert);
  state.counters["us_per_step"] =
      Counter(1e-6 * static_cast<double>(steps_per_ms), Counter::kIsIterationInvariantRate | Counter::kInvert);
  if (const auto* solver = dynamic_cast<const filum::constraints::LagrangeMultiplierSolver*>(scene.constraintSolver())) {
    const auto& stats = solver->statistics();
    state.counters["rows"] = stats.rows;
    state.counters["anchors"] = stats.columns;
    state.counters["solved_per_call"] = stats.solved_columns;
    state.counters["W_nonzeros"] = static_cast<double>(stats.nonzeros);
    state.counters["sparse"] = stats.sparse ? 1 : 0;
    state.counters["refactored"] = stats.refactored ? 1 : 0;  // in the last call: W changed
  }
  state.counters["control_points"] = scene.dofPointCount();
}

/// Steps one simulated millisecond per iteration after a warm-up of `warmup_ms` simulated ms.
void runScene(benchmark::State& state, const json& document, const std::string& name, int warmup_ms) {
  std::unique_ptr<filum::Scene> scene = filum::bench::loadOrSkip(document, name, state);
  if (!scene) return;
  const long steps_per_ms = std::lround(1e-3 / scene->settings().dt);
  filum::bench::timeSteps(*scene, warmup_ms * steps_per_ms, steps_per_ms, state);
  setCounters(state, steps_per_ms, *scene);
}

// ---------------------------------------------------------------------------------------------
// 1. The slides' table.

json figure1a(int control_points, bool probe, const std::string& integrator) {
  const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/paper_constraints.json";
  json document = filum::readJsonFile(path);
  json& components = document["nodes"][0]["components"];
  components[0]["control_points"]["count"] = control_points;
  json kept = json::array();
  for (json& c : components) {
    if (c.value("name", "") == "probe") {
      if (!probe) continue;
      c.erase("release_at");  // held throughout the benchmark
    }
    kept.push_back(c);
  }
  components = kept;
  document["integrator"] = {{"type", integrator}};
  return document;
}

void slides(benchmark::State& state, int control_points, bool probe, const char* integrator, double paper_ms) {
  runScene(state, figure1a(control_points, probe, integrator), "constraints.json (patched)", kWarmupSimulatedMs);
  state.counters["paper_ms"] = paper_ms;
  // paper_ms / (wall ms per iteration): a rate of paper_ms·1e-3 per second of wall time.
  state.counters["speedup"] = benchmark::Counter(paper_ms * 1e-3, benchmark::Counter::kIsIterationInvariantRate);
}

// ---------------------------------------------------------------------------------------------
// 2 and 3. Long threads.

/// n control points 3.7 mm apart (the scene's spacing), c rows in groups spread along.
json longThread(int n, int c, bool reuse, bool sliding = false) {
  const double spacing = 0.1 / 27.0;
  const double length = spacing * (n - 3);
  json components = json::array();
  components.push_back({{"type", "DynamicSpline"},
                        {"control_points", {{"from", {0, 0, 0}}, {"to", {length, 0, 0}}, {"count", n}}},
                        {"radius", 1e-4},
                        {"density", 910}});
  components.push_back({{"type", "SpringForceField"}, {"stretch_stiffness", 1.0}, {"bend_stiffness", 0.001}, {"damping", 1e-5}});
  components.push_back({{"type", "ViscousDamping"}, {"coefficient", 0.5}});
  // Groups {fixed 3, axis 2, plane 1}; the remainder c mod 6 as the first members of a group.
  // Sliding: groups {sliding point 2, plane 1} (the end s = 0 fixed so that the thread hangs).
  const int groups = sliding ? (c + 2) / 3 : (c + 5) / 6;
  int left = c;
  if (sliding) components.push_back({{"type", "FixedPointConstraint"}, {"abscissa", 0.0}});
  for (int g = 0; sliding && g < groups; ++g) {
    const double s = (g + 0.5) / groups, ds = 0.5 / groups;
    if (left >= 2) {
      components.push_back({{"type", "SlidingPointConstraint"}, {"abscissa", s}, {"friction", 1e-5}});
      left -= 2;
    }
    if (left >= 1) {
      components.push_back({{"type", "PointOnPlaneConstraint"}, {"abscissa", s + ds}, {"normal", {0, 0, 1}}});
      left -= 1;
    }
  }
  for (int g = 0; !sliding && g < groups; ++g) {
    const double s = (g + 0.5) / groups, ds = 0.2 / groups;
    if (left >= 3) {
      components.push_back({{"type", "FixedPointConstraint"}, {"abscissa", s}});
      left -= 3;
    }
    if (left >= 2) {
      components.push_back({{"type", "PointOnAxisConstraint"}, {"abscissa", s + ds}, {"axis", {1, 0, 0}}});
      left -= 2;
    }
    if (left >= 1) {
      components.push_back({{"type", "PointOnPlaneConstraint"}, {"abscissa", s + 2 * ds}, {"normal", {0, 0, 1}}});
      left -= 1;
    }
  }
  return json{{"name", "long thread"},
              {"dt", 1e-4},
              {"gravity", {0, 0, -9.81}},
              {"integrator", {{"type", "RungeKutta4"}}},
              {"constraint_solver", {{"type", "LagrangeMultiplierSolver"}, {"reuse", reuse}}},
              {"nodes", json::array({json{{"name", "thread"}, {"components", components}}})}};
}

void scaling(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), c = static_cast<int>(state.range(1));
  runScene(state, longThread(n, c, state.range(2) != 0), "long thread", kScalingWarmupSimulatedMs);
}

void sliding(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), c = static_cast<int>(state.range(1));
  runScene(state, longThread(n, c, true, true), "long thread through holes", kScalingWarmupSimulatedMs);
}

void slidingArgs(benchmark::internal::Benchmark* b) {
  b->ArgNames({"n", "c"});
  for (int c : {9, 30, 90, 300, 500}) b->Args({5000, c});
  for (int n : {625, 1250, 2500}) b->Args({n, 90});
}

void solveOnly(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), c = static_cast<int>(state.range(1));
  std::unique_ptr<filum::Scene> scene = filum::bench::loadOrSkip(longThread(n, c, state.range(2) != 0), "long thread", state);
  if (!scene) return;
  for (int k = 0; k < 100; ++k) scene->step();
  const filum::SceneState& s = scene->state();
  filum::ConstraintRows rows;
  rows.clear();
  for (const filum::Constraint* constraint : scene->constraints()) constraint->buildRows(s, rows);
  filum::VecX force, tendency(s.q.size()), a;
  scene->computeForce(s, force);
  tendency.head(force.size()) = force;
  for (const filum::MechanicalState* body : scene->bodies()) body->solveMass(body->block(tendency));
  auto& solver = dynamic_cast<filum::constraints::LagrangeMultiplierSolver&>(*scene->constraintSolver());
  const filum::FlushDenormals flush_denormals;  // as Scene::step does
  for (auto _ : state) {
    a = tendency;
    solver.solve(scene->constraintProblem(), rows, scene->massInverse(), a);
    benchmark::DoNotOptimize(a.data());
  }
  state.counters["rows"] = solver.statistics().rows;
  state.counters["anchors"] = solver.statistics().columns;
  state.counters["solved_per_call"] = solver.statistics().solved_columns;
  state.counters["W_nonzeros"] = static_cast<double>(solver.statistics().nonzeros);
  state.counters["sparse"] = solver.statistics().sparse ? 1 : 0;
}

void scalingArgs(benchmark::internal::Benchmark* b) {
  b->ArgNames({"n", "c", "reuse"});
  for (int reuse : {1, 0}) {
    // Growing c on the longest thread, and n doubling at fixed c = 90.
    for (int c : {9, 30, 90, 300, 500}) b->Args({5000, c, reuse});
    for (int n : {625, 1250, 2500}) b->Args({n, 90, reuse});
    b->Args({1000, 500, reuse});  // many constraints close together: W dense-ish
  }
}

}  // namespace

BENCHMARK_CAPTURE(slides, 30cp_6rows_RK4, 30, false, "RungeKutta4", 4.5)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(slides, 30cp_9rows_RK4, 30, true, "RungeKutta4", 6.1)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(slides, 50cp_9rows_RK4, 50, true, "RungeKutta4", 10.7)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(slides, 30cp_6rows_SymplecticEuler, 30, false, "SymplecticEuler", 4.5)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(slides, 30cp_9rows_SymplecticEuler, 30, true, "SymplecticEuler", 6.1)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(slides, 50cp_9rows_SymplecticEuler, 50, true, "SymplecticEuler", 10.7)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(scaling)->Apply(scalingArgs)->UseRealTime()->Unit(benchmark::kMillisecond)->MinTime(0.3);
BENCHMARK(sliding)->Apply(slidingArgs)->UseRealTime()->Unit(benchmark::kMillisecond)->MinTime(0.3);
BENCHMARK(solveOnly)->Apply(scalingArgs)->UseRealTime()->Unit(benchmark::kMicrosecond)->MinTime(0.2);
