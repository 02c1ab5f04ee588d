// bench_adaptation: what one adaptive layout change costs — a knot inserted into a 10 cm 3-0
// suture of n control points (Scene::refine: Oslo insertion, the body's mass and rest shape,
// the scene laid out anew, every force field, constraint and the collision pipeline bound again)
// and the step after it (the step matrix lays itself out anew at its assembly), at n = 30 and 165;
// the knot is removed again between iterations (untimed), so every iteration starts from n.
//   build/apps/bench/bench_adaptation --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <nlohmann/json.hpp>

#include "filum/core/curve_body.hpp"
#include "scene_stepping.hpp"

namespace {

using nlohmann::json;

json suture(int n) {
  const json points = {{"from", {0, 0, 0}}, {"to", {0.1, 0, 0}}, {"count", n}};
  const json components = json::array(
      {{{"type", "DynamicSpline"}, {"control_points", points}, {"radius", 1e-4}, {"density", 910}},
       {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}},
       {{"type", "CurvatureBending"}, {"youngs_modulus", 2e9}},
       {{"type", "ViscousDamping"}, {"coefficient", 1.0}},
       {{"type", "SphereCollisionModel"}, {"spacing", 2e-4}, {"self_collision", false}},
       {{"type", "FixedPointConstraint"}, {"abscissa", 0.0}}});
  return {{"name", "bench_adaptation"}, {"dt", 1e-3}, {"duration", 100.0}, {"gravity", {0, 0, -9.81}},
          {"integrator", {{"type", "ImplicitEuler"}}},
          {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"friction", 0.3}}},
          {"nodes", json::array({{{"name", "suture"}, {"components", components}}})}};
}

/// One insertion and its step, per iteration; `with_step` false: the insertion alone.
void insertion(benchmark::State& state, bool with_step) {
  const int n = static_cast<int>(state.range(0));
  auto scene = filum::bench::loadOrSkip(suture(n), "bench_adaptation", state);
  if (!scene) return;
  if (!filum::bench::stepOrSkip(*scene, 50, state, "warm-up: ")) return;
  filum::CurveBody& curve = *scene->bodies().front()->curve();
  // The middle of a span away from the held end: a new knot each time, removed again after.
  const std::vector<double> knots = curve.basis().breakpoints();
  const double s = 0.5 * (knots[knots.size() / 2] + knots[knots.size() / 2 + 1]);
  for (auto _ : state) {
    scene->refine(curve, {s});
    if (with_step && !filum::bench::stepOrSkip(*scene, 1, state)) return;
    state.PauseTiming();
    if (!scene->coarsen(curve, s, 1.0)) {
      state.SkipWithError("the inserted knot did not come out again");
      return;
    }
    state.ResumeTiming();
  }
  state.counters["points"] = n;
}

}  // namespace

BENCHMARK_CAPTURE(insertion, insert_and_relayout, false)->Arg(30)->Arg(165)->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_CAPTURE(insertion, insert_relayout_and_step, true)->Arg(30)->Arg(165)->Unit(benchmark::kMicrosecond)->UseRealTime();
