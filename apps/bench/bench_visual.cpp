// Skinning cost: one update of a GeneralizedCylinder — the SplineAxisMapping of the
// control points down to the axis samples and derivatives, the rotation-minimizing frames and the
// ring vertices and normals — against the number of axis samples (rings), 16 sides per ring, on
// a 30-control-point thread bent into a helix. Linear in the samples: Time / rings (the
// ns_per_ring counter) stays constant. Also the whole VisualScene update of
// apps/scenes/hanging_thread.json (its skin and sphere), the cost `filum run --render` pays per
// frame before drawing.
#include <benchmark/benchmark.h>

#include <cmath>

#include "filum/all_components.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/visual/generalized_cylinder_model.hpp"
#include "filum/visual/visual_scene.hpp"

namespace {

using nlohmann::json;

json helixThread(int samples) {
  json points = json::array();
  for (int i = 0; i < 30; ++i) {
    const double a = 4.0 * 3.141592653589793 * i / 29;
    points.push_back({0.02 * std::cos(a), 0.02 * std::sin(a), 0.05 * a / (2 * 3.141592653589793)});
  }
  return {{"name", "bench visual"},
          {"dt", 1e-4},
          {"nodes", json::array({{{"name", "thread"},
                                  {"components", json::array({{{"type", "DynamicSpline"}, {"control_points", points},
                                                               {"mass", 1e-3}, {"radius", 1e-3}},
                                                              {{"type", "GeneralizedCylinder"}, {"samples", samples},
                                                               {"sides", 16}}})}}})}};
}

void BM_SkinUpdate(benchmark::State& state) {
  const int rings = static_cast<int>(state.range(0));
  auto scene = filum::loadScene(helixThread(rings), "bench", filum::app::makeFactory());
  filum::visual::VisualScene visuals(*scene);
  filum::visual::VisualModel& skin = *visuals.models().front();
  filum::SceneState s = scene->state();
  for (auto _ : state) {
    skin.update(s);
    benchmark::DoNotOptimize(skin.mesh().vertices.data());
  }
  state.counters["rings"] = rings;
  state.counters["vertices"] = skin.mesh().vertexCount();
  state.counters["ns_per_ring"] =
      benchmark::Counter(rings * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_SkinUpdate)->RangeMultiplier(4)->Range(16, 16384)->Unit(benchmark::kMicrosecond);

void BM_HangingThreadVisualUpdate(benchmark::State& state) {
  auto scene = filum::loadScene(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/hanging_thread.json", filum::app::makeFactory());
  filum::visual::VisualScene visuals(*scene);
  for (auto _ : state) visuals.update(scene->state());
}
BENCHMARK(BM_HangingThreadVisualUpdate)->Unit(benchmark::kMicrosecond);

}  // namespace
