// bench_applications: the surgical applications in wall time per simulated millisecond — the
// shipped salpingectomy.json, intestine.json, guidewire.json, catheter_device.json, catheter.json,
// coil_in_sac.json, coil.json and stitch.json
// played whole with their instruments, navigation metrics or hub device (as `filum run` plays them:
// the instruments' drivers, jaws and metrics, the device's servo ticks between the steps), and the
// small bowel's cost against its length: a bowel of 0.5, 1, 2 and 4 m (radius 1.5 cm, soft
// tissue, a control point every 2.5 cm, contact spheres every 1.5 cm with self-collision and
// friction 0.3) laid as a serpentine on the posterior abdominal wall (a plane), its turns relaxing
// into loops that touch. The grid broad phase keeps self-collision near linear in the length;
// what grows faster is the contact solve (dense in the contact rows, contact_newton.hpp).
// And coaxial instruments: a 100-node guidewire pushed through a 100-node catheter (both 30 cm,
// 3 mm segments, held at both ends and sagging under gravity): the wire lies on the lumen's
// floor along its whole length, the worst case for the contact rows: measured 1140 ms per
// simulated ms (median of 3) with ~430 lumen contacts (1300 rows), where the issue asks 1; 735
// (one run) after W's column assembly, 27 (median of 3) since the band step merges the two bodies
// along each other and Newton's products with W go through the bands (2026-11-27), 17.2 since W's
// diagonal comes from A⁻¹'s blocks within a widened range (2026-11-29, the old build 27.7 that day):
// docs/vessels.md.
//   build/apps/bench/bench_applications --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// (about 50 minutes: catheter.json alone takes 4-5 minutes a run, coil.json about 4; filter them
// out with --benchmark_filter=-'application/(catheter|coil)/' for the rest.)
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "filum/haptics/hub_device.hpp"
#include "filum/haptics/instrument_set.hpp"
#include "filum/haptics/navigation_metrics.hpp"
#include "scene_stepping.hpp"

namespace {

using nlohmann::json;

/// The whole scripted run of apps/scenes/<file> per iteration (loading untimed).
void application(benchmark::State& state, const std::string& file) {
  const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/" + file;
  double simulated = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    const json document = filum::readJsonFile(path);
    auto scene = filum::bench::loadOrSkip(document, path, state);
    if (!scene) return;
    auto instruments = filum::haptics::InstrumentSet::fromScene(document, path, *scene);
    auto navigation = filum::haptics::NavigationMetrics::fromScene(document, path, *scene);
    auto hub_device = filum::haptics::HubDevice::fromScene(document, path, *scene, scene->settings().duration);
    const double dt = scene->settings().dt;
    const long steps = std::lround(scene->settings().duration / dt);
    if (navigation) navigation->start(*scene);
    state.ResumeTiming();
    for (long k = 0; k < steps; ++k) {
      if (instruments) instruments->beforeStep(*scene);
      if (hub_device) hub_device->beforeStep(*scene);
      const filum::StepReport report = scene->step();
      if (!report.ok) {
        state.SkipWithError(report.message.c_str());
        return;
      }
      if (instruments) instruments->afterStep(*scene);
      if (hub_device) hub_device->afterStep(*scene);
      if (navigation) navigation->afterStep(*scene, dt);
    }
    simulated += scene->settings().duration;
  }
  // Simulated seconds per wall second, inverted: wall time per simulated time (ms per ms).
  using benchmark::Counter;
  state.counters["wall_ms_per_sim_ms"] = Counter(simulated, Counter::kIsRate | Counter::kInvert);
}

/// A serpentine of `length` metres: rows of 20 cm along x, 4.5 cm apart, joined by half circles;
/// a point every `spacing` metres along it, at height z.
std::vector<std::array<double, 3>> serpentine(double length, double spacing, double z) {
  const double row = 0.2, pitch = 0.045, turn = pitch / 2;
  std::vector<std::array<double, 3>> points;
  double y = 0.0, walked = 0.0;
  bool forward = true;
  auto at = [&](double t) -> std::array<double, 3> {  // t along the current row and its turn
    const double x0 = forward ? -row / 2 : row / 2, sign = forward ? 1.0 : -1.0;
    if (t <= row) return {x0 + sign * t, y, z};
    const double angle = (t - row) / turn;  // along the half circle
    return {x0 + sign * (row + turn * std::sin(angle)), y + turn - turn * std::cos(angle), z};
  };
  double next = 0.0;
  while (next <= length + 1e-9) {
    const double piece = row + M_PI * turn;
    while (next <= length + 1e-9 && next - walked <= piece) {
      points.push_back(at(next - walked));
      next += spacing;
    }
    walked += piece;
    y += pitch;
    forward = !forward;
  }
  return points;
}

json bowelOnTheWall(double length) {
  const double radius = 0.015, k = 200.0, linear_density = 1050 * M_PI * radius * radius;
  const auto points = serpentine(length, 0.025, radius);
  json control_points = json::array();
  for (const auto& p : points) control_points.push_back({p[0], p[1], p[2]});
  const double rows = std::ceil(length / (0.2 + M_PI * 0.0225));
  const json components = json::array(
      {{{"type", "DynamicSpline"}, {"control_points", control_points}, {"radius", radius}, {"density", 1050}},
       {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 1e5}},
       {{"type", "CurvatureBending"}, {"youngs_modulus", 1e5}},
       {{"type", "ViscousDamping"}, {"coefficient", 2.0}},
       {{"type", "TissueAttachment"}, {"count", static_cast<int>(60 * length)}, {"stiffness", k},
        {"damping", 2.0 * std::sqrt(k * linear_density)}, {"rest_length", "initial"},
        {"root", {{"from", {-0.06, 0.0, -0.03}}, {"to", {0.06, 0.045 * rows, -0.03}}}}},
       {{"type", "SphereCollisionModel"}, {"spacing", radius}, {"self_collision", true}}});
  return {{"name", "bench_applications bowel"}, {"dt", 1e-3}, {"duration", 100.0}, {"gravity", {0, 0, -9.81}},
          {"integrator", {{"type", "ImplicitEuler"}}},
          {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"friction", 0.3}}},
          {"nodes", json::array({{{"name", "bowel"}, {"components", components}},
                                 {{"name", "wall"},
                                  {"components", json::array({{{"type", "PlaneObstacle"}, {"point", {0, 0, 0}},
                                                               {"normal", {0, 0, 1}}, {"friction", 0.2}}})}}})}};
}

void bowelLength(benchmark::State& state) {
  const double length = state.range(0) / 10.0;
  auto scene = filum::bench::loadOrSkip(bowelOnTheWall(length), "bench_applications", state);
  if (!scene) return;
  // 0.3 s untimed: the turns relax into loops that touch; then 10 steps (10 simulated ms) per iteration.
  filum::bench::timeSteps(*scene, 300, 10, state);
  using benchmark::Counter;
  state.counters["wall_ms_per_sim_ms"] = Counter(1e-2, Counter::kIsIterationInvariantRate | Counter::kInvert);
  state.counters["metres"] = length;
}

/// A 0.035" nitinol-core guidewire (r = 0.445 mm, E I ≈ 6e-5 N m²) inside a 5 F catheter (outer
/// radius 0.83 mm, lumen 0.53 mm, a polymer of E = 2 GPa), 100 nodes each over 30 cm, the
/// catheter held at its hub and tip, the wire pushed from its hub at 5 cm/s.
json wireInCatheter(bool chord_steps = true) {
  const double length = 0.3;
  const json catheter = json::array(
      {{{"type", "FramedChain"}, {"nodes", {{"from", {0, 0, 0}}, {"to", {length, 0, 0}}, {"count", 100}}},
        {"radius", 8.3e-4}, {"density", 1150}},
       {{"type", "ChainElasticity"}, {"youngs_modulus", 2e9}, {"poisson_ratio", 0.4}},
       {{"type", "ViscousDamping"}, {"coefficient", 5.0}},
       {{"type", "ClampConstraint"}, {"abscissa", 0.0}},
       {{"type", "FixedPointConstraint"}, {"abscissa", 1.0}},
       {{"type", "SphereCollisionModel"}, {"spacing", 8.3e-4}, {"self_collision", false}, {"lumen_radius", 5.3e-4},
        {"lumen_friction", 0.05}}});
  const json wire = json::array(
      {{{"type", "FramedChain"}, {"nodes", {{"from", {-0.05, 0, 0}}, {"to", {length - 0.05, 0, 0}}, {"count", 100}}},
        {"radius", 4.45e-4}, {"density", 4000}},
       {{"type", "ChainElasticity"}, {"youngs_modulus", 2e9}, {"poisson_ratio", 0.3}},
       {{"type", "ViscousDamping"}, {"coefficient", 5.0}},
       {{"type", "FixedPointConstraint"}, {"abscissa", 0.0},
        {"path", {{{"time", 0.0}, {"position", {-0.05, 0, 0}}}, {{"time", 100.0}, {"position", {4.95, 0, 0}}}}}},
       {{"type", "SphereCollisionModel"}, {"spacing", 4.45e-4}, {"self_collision", false}, {"inside", "catheter"}}});
  return {{"name", "bench_applications wire in catheter"}, {"dt", 1e-3}, {"duration", 100.0}, {"gravity", {0, 0, -9.81}},
          {"integrator", {{"type", "ImplicitEuler"}}},
          {"constraint_solver", {{"type", "LagrangeMultiplierSolver"}, {"newton_chord_steps", chord_steps}}},
          {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}}},
          {"nodes", json::array({{{"name", "catheter"}, {"components", catheter}}, {{"name", "wire"}, {"components", wire}}})}};
}

/// `chord_steps` false: the contact Newton factors at every iteration (newton_chord_steps).
void wireThroughCatheter(benchmark::State& state, bool chord_steps) {
  auto scene = filum::bench::loadOrSkip(wireInCatheter(chord_steps), "bench_applications", state);
  if (!scene) return;
  // 0.2 s untimed: the wire comes down onto the lumen's floor; then 10 steps per iteration.
  filum::bench::timeSteps(*scene, 200, 10, state);
  using benchmark::Counter;
  state.counters["wall_ms_per_sim_ms"] = Counter(1e-2, Counter::kIsIterationInvariantRate | Counter::kInvert);
  state.counters["contacts"] = scene->collisionPipeline()->contactCount();
}

}  // namespace

BENCHMARK_CAPTURE(application, salpingectomy, std::string("salpingectomy.json"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(application, intestine, std::string("intestine.json"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(application, guidewire, std::string("guidewire.json"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(application, catheter_device, std::string("catheter_device.json"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(application, catheter, std::string("catheter.json"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(application, coil_in_sac, std::string("coil_in_sac.json"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(application, coil, std::string("coil.json"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(application, stitch, std::string("stitch.json"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
BENCHMARK(bowelLength)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(wireThroughCatheter, chords, true)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(wireThroughCatheter, no_chords, false)->UseRealTime()->Unit(benchmark::kMillisecond);
