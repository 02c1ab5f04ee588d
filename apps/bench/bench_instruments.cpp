// bench_instruments: what two instruments cost per step — a 10 cm 3-0 silk suture
// hanging from its top end (apps/scenes/instruments.json's), grasped by two graspers from either
// side (at 4 and 7 cm, closed by 0.3 s) that then carry it slowly to and fro, against the same
// scene without them (the suture hanging, the same contact pipeline). Implicit Euler, dt = 1 ms.
// Reported: wall ms per simulated ms (the instruments' work between the steps counted: their
// poses, the jaws' tests, slips, metrics; and in the step their holds and shaft contacts).
//   build/apps/bench/bench_instruments --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <nlohmann/json.hpp>

#include "filum/haptics/instrument_set.hpp"
#include "scene_stepping.hpp"

namespace {

using nlohmann::json;

json grasper(const std::string& name, double z, double side) {
  // From y = side · 7 cm to 1 cm of the suture, jaws closing by 0.3 s, then to and fro along x.
  json path = json::array({{{"time", 0.0}, {"position", {0, side * 0.07, z}}, {"direction", {0, -side, 0}},
                            {"roll", 1.5708}, {"jaw", 1}},
                           {{"time", 0.15}, {"position", {0, side * 0.01, z}}},
                           {{"time", 0.3}, {"position", {0, side * 0.01, z}}, {"jaw", 0}}});
  for (int k = 1; k <= 200; ++k)
    path.push_back({{"time", 0.3 + 0.5 * k}, {"position", {(k % 2 ? 0.005 : -0.005) * side, side * 0.01, z}}});
  return {{"name", name}, {"type", "Grasper"}, {"holding_force", 2.0}, {"path", path}};
}

json sutureScene(bool instruments) {
  const json points = {{"from", {0, 0, 0}}, {"to", {0, 0, -0.1}}, {"count", 40}};
  const json components = json::array(
      {{{"type", "DynamicSpline"}, {"control_points", points}, {"radius", 1.1e-4}, {"density", 1300}},
       {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 8.7e9}},
       {{"type", "CurvatureBending"}, {"youngs_modulus", 5e8}},
       {{"type", "ViscousDamping"}, {"coefficient", 1.0}},
       {{"type", "SphereCollisionModel"}, {"spacing", 2.2e-4}, {"self_collision", false}},
       {{"type", "FixedPointConstraint"}, {"abscissa", 0.0}}});
  json document = {{"name", "bench_instruments"}, {"dt", 1e-3}, {"duration", 100.0}, {"gravity", {0, 0, -9.81}},
                   {"integrator", {{"type", "ImplicitEuler"}}},
                   {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"friction", 0.3}}},
                   {"nodes", json::array({{{"name", "suture"}, {"components", components}}})}};
  if (instruments) document["instruments"] = json::array({grasper("left", -0.04, -1.0), grasper("right", -0.07, 1.0)});
  return document;
}

void suture(benchmark::State& state, bool with_instruments) {
  const json document = sutureScene(with_instruments);
  auto scene = filum::bench::loadOrSkip(document, "bench_instruments", state);
  if (!scene) return;
  std::unique_ptr<filum::haptics::InstrumentSet> instruments;
  try {
    instruments = filum::haptics::InstrumentSet::fromScene(document, "bench_instruments", *scene);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  auto step = [&]() {
    if (instruments) instruments->beforeStep(*scene);
    const filum::StepReport report = scene->step();
    if (report.ok && instruments) instruments->afterStep(*scene);
    if (!report.ok) state.SkipWithError(report.message.c_str());
    return report.ok;
  };
  for (int k = 0; k < 400; ++k)  // warm-up: both graspers hold by 0.3 s
    if (!step()) return;
  if (instruments && !(instruments->instrument(0).holding() && instruments->instrument(1).holding())) {
    state.SkipWithError("the graspers did not catch the suture");
    return;
  }
  for (auto _ : state)
    for (int k = 0; k < 10; ++k)
      if (!step()) return;
  using benchmark::Counter;
  state.counters["wall_ms_per_sim_ms"] = Counter(1e-2, Counter::kIsIterationInvariantRate | Counter::kInvert);
}

}  // namespace

BENCHMARK_CAPTURE(suture, two_graspers_grasping, true)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(suture, no_instruments, false)->UseRealTime()->Unit(benchmark::kMillisecond);
