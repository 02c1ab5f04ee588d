// bench_rod: wall time per simulated ms of a rod (FramedChain + ChainElasticity + RodEndFrame:
// a catheter-like polymer rod, L = 0.2 m, r = 1 mm, E = 30 MPa, ν = 0.5, 1150 kg/m³, drag 2/s)
// stepped by ImplicitEuler at dt = 1 ms, as the node count grows. Two cases:
//   free:  built in at s = 0 (FixedPointConstraint + RodEndFrame), swinging under gravity from
//          horizontal (no contact);
//   plane: lying on a table (PlaneObstacle, unilateral contact rows, Coulomb friction 0.3), its
//          s = 0 end dragged sideways along the table at 5 cm/s by a FixedPointConstraint path;
//          the _dense variants solve the contact Newton's steps by a dense LU instead of through
//          the step matrix's band (newton_linear_solve, lagrange_multiplier_solver.hpp); the
//          _no_chords one factors the contact Newton's system at every iteration
//          (newton_chord_steps false: contact_newton.hpp, chord steps).
// One iteration = 10 steps (10 simulated ms), after 100 ms untimed. Counters: wall_ms_per_sim_ms
// (the real-time figure: <= 1 runs in real time) and us_per_step. Run:
//   build/apps/bench/bench_rod --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "scene_stepping.hpp"

namespace {

using nlohmann::json;

json rodScene(int nodes, bool plane, const char* newton_linear_solve = "auto", bool chord_steps = true) {
  const double height = plane ? 1.2e-3 : 0.05;  // just above the table (it settles on it in the warm-up)
  json rod = {{"name", "rod"},
              {"components",
               {{{"type", "FramedChain"},
                 {"nodes", {{"from", {0, 0, height}}, {"to", {0.2, 0, height}}, {"count", nodes}}},
                 {"radius", 1e-3},
                 {"density", 1150}},
                {{"type", "ChainElasticity"}, {"youngs_modulus", 3e7}, {"poisson_ratio", 0.5}},
                {{"type", "ViscousDamping"}, {"coefficient", 2.0}}}}};
  json& components = rod["components"];
  if (plane) {
    const json path = json::array({json{{"time", 0.0}, {"position", {0.0, 0.0, height}}},
                                   json{{"time", 10.0}, {"position", {0.0, 0.5, height}}}});
    components.push_back({{"type", "FixedPointConstraint"}, {"abscissa", 0.0}, {"path", path}});
    components.push_back({{"type", "SphereCollisionModel"}, {"spacing", 1.5e-3}});
  } else {
    components.push_back({{"type", "RodEndFrame"}});
    components.push_back({{"type", "FixedPointConstraint"}, {"abscissa", 0.0}});
  }
  json document = {{"dt", 1e-3},
                   {"duration", 100.0},
                   {"gravity", {0, 0, -9.81}},
                   {"integrator", {{"type", "ImplicitEuler"}}},
                   {"constraint_solver",
                    {{"type", "LagrangeMultiplierSolver"},
                     {"newton_linear_solve", newton_linear_solve},
                     {"newton_chord_steps", chord_steps}}},
                   {"nodes", {rod}}};
  if (plane) {
    document["collision"] = {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"friction", 0.3}};
    document["nodes"].push_back(
        {{"name", "table"},
         {"components", {{{"type", "PlaneObstacle"}, {"point", {0, 0, 0}}, {"normal", {0, 0, 1}}, {"friction", 0.3}}}}});
  }
  return document;
}

void rod(benchmark::State& state, int nodes, bool plane, const char* newton_linear_solve = "auto",
         bool chord_steps = true) {
  auto scene = filum::bench::loadOrSkip(rodScene(nodes, plane, newton_linear_solve, chord_steps), "bench_rod", state);
  if (!scene) return;
  if (!filum::bench::stepOrSkip(*scene, 100, state, "warm-up: ")) return;
  for (auto _ : state)
    if (!filum::bench::stepOrSkip(*scene, 10, state)) break;
  using benchmark::Counter;
  state.counters["wall_ms_per_sim_ms"] = Counter(1e-2, Counter::kIsIterationInvariantRate | Counter::kInvert);
  state.counters["us_per_step"] = Counter(1e-5, Counter::kIsIterationInvariantRate | Counter::kInvert);
}

}  // namespace

BENCHMARK_CAPTURE(rod, free_n21, 21, false)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rod, free_n50, 50, false)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rod, free_n100, 100, false)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rod, free_n400, 400, false)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rod, plane_n21, 21, true)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rod, plane_n50, 50, true)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rod, plane_n100, 100, true)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rod, plane_n400, 400, true)->UseRealTime()->Unit(benchmark::kMillisecond);
// The contact Newton's steps by a dense LU always (the structured solve's reference).
BENCHMARK_CAPTURE(rod, plane_n50_dense, 50, true, "dense")->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rod, plane_n100_dense, 100, true, "dense")->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rod, plane_n100_no_chords, 100, true, "auto", false)->UseRealTime()->Unit(benchmark::kMillisecond);
