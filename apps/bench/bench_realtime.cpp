// bench_realtime: is a stiff thread real time? Wall time per simulated millisecond,
// largest strain and energy drift of the benchmark rope (apps/scenes/rope.json: 1 m, 0.1 kg,
// radius 5 mm, E = 1e8 Pa, held at one end, released horizontally) at n = 30, 50, 165, 1000
// control points with each implicit scheme at dt = 1 ms, and with the explicit schemes at the
// largest step their stability allows (a shorter run: their steps are ~1e4 times smaller); then
// the reference scenes (apps/scenes/*.json) as they are.
//
// Wall time counts Scene::step only (no output). Each configuration runs `--repetitions` times
// (default 5) from the same start; the figure is the median of the runs. Max strain is
// max |ε| = max | |P'(s)| / |P0'(s)| − 1 | over 8 abscissas per span, sampled every 10 ms of
// simulated time. Energy drift is (E(T) − E(0)) / (m g ℓ) with ℓ = 1 m, or / |E(0)| in a scene
// without gravity: kinetic + gravity + elastic; backward Euler dissipates, so it is negative.
//
// Output: a table on stdout, realtime.csv and, with --plot, realtime.png (apps/tools/
// plot_realtime.py: strain against wall time per simulated ms, one point per configuration).
//   build/apps/bench/bench_realtime [--quick] [--repetitions R] [--duration T] [--out DIR] [--plot]
//                                   [--sizes N...] [--schemes TEXT...] [--scenes NAME...] [--step-kinds]
// --quick: n = 30 and 165 only, 1 s, 3 repetitions, no explicit schemes nor reference scenes.
// --sizes, --schemes (labels containing one of the texts), --scenes (file stems): run only those;
// --scenes alone skips the rope, --sizes alone the reference scenes (to profile one of them).
// --step-kinds: the implicit steps by kind (reused, fresh, refreshed, corrected, reused+chord), mean wall each.
// Built with -DFILUM_WITH_PEERS=ON it also runs the same rope in Bullet at 4 and 64 solver
// iterations and in MuJoCo (n <= 165) — apps/bench/peers/ — and adds their rows to the CSV and
// the plot.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "filum/all_components.hpp"
#include "filum/core/constraint_solver.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/mechanics/implicit_euler.hpp"
#include "filum/mechanics/implicit_midpoint.hpp"
#include "validation/stability.hpp"

namespace {

using nlohmann::json;

bool print_step_kinds = false;  // --step-kinds

struct Scheme {
  std::string label;  // as printed and in the CSV
  json integrator;
  bool explicit_scheme = false;
};

/// Steps of an implicit solver by what they did, with their wall time: reused an earlier matrix
/// (and its estimate passed), assembled a fresh one, reused and were taken again (refreshed), went
/// on to Newton after the estimate (corrected), reused and passed on a second chord iteration
/// (reused+chord). Printed with --step-kinds.
struct StepKinds {
  static constexpr int kKinds = 5;
  static constexpr const char* kNames[kKinds] = {"reused", "fresh", "refreshed", "corrected", "reused+chord"};
  double wall[kKinds] = {0, 0, 0, 0, 0};  // s
  long count[kKinds] = {0, 0, 0, 0, 0};
};

struct Figures {
  double wall_ms_per_sim_ms = 0.0;  // median over repetitions
  double max_strain = 0.0;
  double energy_drift = 0.0;  // (E(T) − E(0)) / (m g ℓ)
  double dt = 0.0;
  double simulated = 0.0;
  long corrections = -1, estimates = -1, halvings = -1, reuses = -1, refreshes = -1;  // implicit solvers only
  StepKinds kinds;  // implicit solvers, first run
  filum::ContactSolveTally contact;  // the constraint solver's contact solves, first run
  std::string failure;
};

json ropeDocument(int n, const json& integrator, double dt, double duration) {
  json document = filum::readJsonFile(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/rope.json");
  document["dt"] = dt;
  document["duration"] = duration;
  document["integrator"] = integrator;
  json& components = document["nodes"][0]["components"];
  components[0]["control_points"]["count"] = n;
  // Only the mechanical side: visual components cost nothing in a step but need not be built.
  components.erase(components.size() - 1);
  components.erase(components.size() - 1);
  return document;
}

/// max | |P'(s)| / |P0'(s)| − 1 | over 8 abscissas per span of every spline body.
double maxStrain(const filum::Scene& scene) {
  double strain = 0.0;
  for (const filum::MechanicalState* body : scene.bodies()) {
    const auto* spline = body->curve();
    if (!spline) continue;
    const auto q = spline->block(scene.state().q);
    const int samples = 8 * spline->pointCount();
    filum::geometry::BasisRow row;
    for (int k = 0; k <= samples; ++k) {
      spline->basis().evaluate(static_cast<double>(k) / samples, row);
      const double rest = filum::geometry::curveTangent(row, spline->initialPositions()).norm();
      strain = std::max(strain, std::abs(filum::geometry::curveTangent(row, q).norm() / rest - 1.0));
    }
  }
  return strain;
}

double totalMass(const filum::Scene& scene) {
  double mass = 0.0;
  for (const filum::MechanicalState* body : scene.bodies())
    if (const auto* spline = body->curve()) mass += spline->mass();
  return mass;
}

const filum::mechanics::ImplicitStepSolver* implicitSolver(const filum::Scene& scene) {
  if (const auto* euler = dynamic_cast<const filum::mechanics::ImplicitEuler*>(&scene.integrator())) return &euler->solver();
  if (const auto* midpoint = dynamic_cast<const filum::mechanics::ImplicitMidpoint*>(&scene.integrator()))
    return &midpoint->solver();
  return nullptr;
}

/// Runs the scene of `document` `repetitions` times for its duration; strain and drift of the
/// first run (runs are bit-identical), wall time the median.
Figures measure(const json& document, const std::string& name, int repetitions) {
  Figures figures;
  std::vector<double> walls;
  for (int r = 0; r < repetitions; ++r) {
    std::unique_ptr<filum::Scene> scene = filum::loadScene(document, name, filum::app::makeFactory());
    scene->init();
    const double dt = scene->settings().dt;
    const long steps = std::lround(scene->settings().duration / dt);
    const long sample_every = std::max(1L, std::lround(0.01 / dt));
    const double e0 = scene->energy(scene->state()).total();
    // m g ℓ with ℓ = 1 m; without gravity (taut string) the initial energy itself.
    const double scale = std::max(totalMass(*scene) * scene->settings().gravity.norm() * 1.0, std::abs(e0));
    double strain = 0.0, wall = 0.0;
    StepKinds kinds;
    const auto* solver = implicitSolver(*scene);
    for (long k = 0; k < steps; ++k) {
      const long reuses = solver ? solver->reuses() : 0, refreshes = solver ? solver->refreshes() : 0,
                 corrections = solver ? solver->corrections() : 0, chords = solver ? solver->secondChords() : 0;
      const auto start = std::chrono::steady_clock::now();
      const filum::StepReport report = scene->step();
      const double step_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      wall += step_wall;
      if (solver) {
        const int kind = solver->corrections() > corrections ? 3
                         : solver->refreshes() > refreshes   ? 2
                         : solver->secondChords() > chords   ? 4
                         : solver->reuses() > reuses         ? 0
                                                             : 1;
        kinds.wall[kind] += step_wall;
        ++kinds.count[kind];
      }
      if (!report.ok) {
        figures.failure = report.message;
        return figures;
      }
      if (r == 0 && k % sample_every == 0) strain = std::max(strain, maxStrain(*scene));
    }
    walls.push_back(1e3 * wall / (1e3 * steps * dt));
    if (solver && r == 0) figures.kinds = kinds;
    if (r == 0 && scene->constraintSolver()) figures.contact = scene->constraintSolver()->contactTally();
    if (r == 0) {
      figures.max_strain = std::max(strain, maxStrain(*scene));
      figures.energy_drift = (scene->energy(scene->state()).total() - e0) / scale;
      figures.dt = dt;
      figures.simulated = steps * dt;
      if (const auto* solver = implicitSolver(*scene)) {
        figures.corrections = solver->corrections();
        figures.estimates = solver->estimates();
        figures.halvings = solver->halvings();
        figures.reuses = solver->reuses();
        figures.refreshes = solver->refreshes();
      }
    }
  }
  std::sort(walls.begin(), walls.end());
  figures.wall_ms_per_sim_ms = walls[walls.size() / 2];
  return figures;
}

void printRow(std::FILE* csv, const std::string& problem, int n, const std::string& scheme, const Figures& f) {
  if (!f.failure.empty()) {
    std::printf("%-22s %5d  %-26s FAILED: %s\n", problem.c_str(), n, scheme.c_str(), f.failure.c_str());
    std::fprintf(csv, "%s,%d,%s,%g,,,,,,,,,failed\n", problem.c_str(), n, scheme.c_str(), f.dt);
    return;
  }
  std::printf("%-22s %5d  %-26s dt %-8.2g %9.4f ms/ms  strain %.2e  drift %+.2e", problem.c_str(), n, scheme.c_str(), f.dt,
              f.wall_ms_per_sim_ms, f.max_strain, f.energy_drift);
  if (f.estimates >= 0) std::printf("  corrected %ld/%ld halved %ld", f.corrections, f.estimates, f.halvings);
  if (f.reuses > 0) std::printf(" reused %ld refreshed %ld", f.reuses, f.refreshes);
  if (f.contact.solves > 0)
    std::printf("  contact solves %ld: converged %.1f %%, fell back %ld, %.2g iterations each (%.2g chords), worst residual %.2g x tol",
                f.contact.solves, 100.0 * f.contact.converged / f.contact.solves, f.contact.fell_back,
                static_cast<double>(f.contact.iterations) / f.contact.solves,
                static_cast<double>(f.contact.chord_steps) / f.contact.solves, f.contact.worst_ratio);
  std::printf("\n");
  if (print_step_kinds && f.estimates >= 0) {
    std::printf("%-22s %5s  steps by kind (first run): ", "", "");
    for (int k = 0; k < StepKinds::kKinds; ++k)
      if (f.kinds.count[k] > 0)
        std::printf(" %s %ld x %.1f us", StepKinds::kNames[k], f.kinds.count[k], 1e6 * f.kinds.wall[k] / f.kinds.count[k]);
    std::printf("\n");
  }
  std::fflush(stdout);
  std::fprintf(csv, "%s,%d,%s,%g,%g,%.6g,%.6g,%.6g,%ld,%ld,%ld,%ld,ok\n", problem.c_str(), n, scheme.c_str(), f.dt,
               f.simulated, f.wall_ms_per_sim_ms, f.max_strain, f.energy_drift, f.corrections, f.halvings, f.reuses,
               f.refreshes);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"bench_realtime: wall time per simulated ms, strain and energy drift of a stiff rope and the reference scenes"};
  bool quick = false, plot = false;
  int repetitions = 5;
  double duration = 10.0;
  std::string out = "apps/bench/results/realtime";
  cli.add_flag("--quick", quick, "n = 30 and 165, 1 s, 3 repetitions, implicit schemes only");
  cli.add_option("--repetitions", repetitions, "runs per configuration (median reported)")->check(CLI::Range(1, 100));
  cli.add_option("--duration", duration, "simulated seconds of each rope run")->check(CLI::Range(1e-3, 1e3));
  cli.add_option("--out", out, "directory for realtime.csv (and realtime.png)");
  cli.add_flag("--plot", plot, "draw realtime.png with apps/tools/plot_realtime.py");
  std::vector<int> sizes;
  std::vector<std::string> scheme_filter, scene_filter;
  cli.add_option("--sizes", sizes, "rope sizes (default 30 50 165 1000; --quick: 30 165)")->check(CLI::Range(4, 100000));
  cli.add_option("--schemes", scheme_filter, "rope schemes whose label contains one of these texts");
  cli.add_flag("--step-kinds", print_step_kinds, "also print the implicit steps by kind (reused, fresh, refreshed, corrected, reused+chord) with their mean wall time");
  cli.add_option("--scenes", scene_filter, "reference scenes (file stems in apps/scenes) to run; alone, no rope");
  CLI11_PARSE(cli, argc, argv);
  if (quick) {
    repetitions = std::min(repetitions, 3);
    duration = 1.0;
  }
  // --scenes: every name must be a scene file, checked before anything runs.
  const std::string scene_dir = std::string(FILUM_SOURCE_DIR) + "/apps/scenes";
  for (const std::string& name : scene_filter)
    if (!std::filesystem::exists(scene_dir + "/" + name + ".json")) {
      std::fprintf(stderr, "error: --scenes: expected the stem of a scene file in %s, found \"%s\"\n", scene_dir.c_str(),
                   name.c_str());
      return 2;
    }
  const bool run_rope = !sizes.empty() || scene_filter.empty();
  const bool run_scenes = !scene_filter.empty() || (sizes.empty() && !quick);
  if (sizes.empty()) sizes = quick ? std::vector<int>{30, 165} : std::vector<int>{30, 50, 165, 1000};
  if (!run_rope) sizes.clear();
  const auto selected = [&](const std::string& label) {
    return scheme_filter.empty() || std::any_of(scheme_filter.begin(), scheme_filter.end(), [&](const std::string& text) {
             return label.find(text) != std::string::npos;
           });
  };
  std::filesystem::create_directories(out);
  const std::string csv_path = out + "/realtime.csv";
  std::FILE* csv = std::fopen(csv_path.c_str(), "w");
  if (!csv) {
    std::fprintf(stderr, "error: cannot write %s\n", csv_path.c_str());
    return 4;
  }
  std::fprintf(csv, "problem,n,scheme,dt,simulated_s,wall_ms_per_sim_ms,max_strain,energy_drift,corrections,halvings,reuses,refreshes,status\n");

  const std::vector<Scheme> implicit_schemes = {
      {"implicit Euler linearized", {{"type", "ImplicitEuler"}}},
      {"implicit Euler lin. fresh", {{"type", "ImplicitEuler"}, {"reuse_factorization", false}}},
      {"implicit Euler B-W only", {{"type", "ImplicitEuler"}, {"newton_iterations", 1}}},
      {"implicit Euler Newton", {{"type", "ImplicitEuler"}, {"solve", "newton"}}},
      {"implicit midpoint lin.", {{"type", "ImplicitMidpoint"}}},
  };
  const std::vector<Scheme> explicit_schemes = {
      {"symplectic Euler", {{"type", "SymplecticEuler"}}, true},
      {"RK4", {{"type", "RungeKutta4"}}, true},
  };
  if (run_rope)
    std::printf("rope: 1 m, 0.1 kg, r = 5 mm, E = 1e8 Pa; median of %d runs; %g s simulated (explicit: 0.05 s)\n",
              repetitions, duration);
  for (int n : sizes) {
    for (const Scheme& scheme : implicit_schemes)
      if (selected(scheme.label))
        printRow(csv, "rope", n, scheme.label, measure(ropeDocument(n, scheme.integrator, 1e-3, duration), "rope", repetitions));
    if (quick || n > 165 || !std::any_of(explicit_schemes.begin(), explicit_schemes.end(),
                                         [&](const Scheme& scheme) { return selected(scheme.label); }))
      continue;  // explicit steps at n = 1000 would take hours
    // Explicit schemes at 90 % of their stability limit ω_max dt = 2 (symplectic) or 2√2 (RK4).
    const double omega = [&] {
      auto scene = filum::loadScene(ropeDocument(n, implicit_schemes[0].integrator, 1e-3, duration), "rope",
                                    filum::app::makeFactory());
      scene->init();
      return filum::validation::stiffestFrequency(*scene, scene->state());
    }();
    for (const Scheme& scheme : explicit_schemes) {
      if (!selected(scheme.label)) continue;
      const double limit = scheme.label == "RK4" ? 2.0 * std::sqrt(2.0) : 2.0;
      printRow(csv, "rope", n, scheme.label,
               measure(ropeDocument(n, scheme.integrator, 0.9 * limit / omega, std::min(duration, 0.05)), "rope", repetitions));
    }
  }
  if (run_scenes) {
    std::printf("reference scenes, as they are (their own dt and integrator), %g s or their duration\n", duration);
    std::vector<std::filesystem::path> scenes;
    for (const auto& entry : std::filesystem::directory_iterator(scene_dir))
      if (entry.path().extension() == ".json" &&
          (scene_filter.empty() || std::count(scene_filter.begin(), scene_filter.end(), entry.path().stem().string())))
        scenes.push_back(entry.path());
    std::sort(scenes.begin(), scenes.end());
    for (const auto& path : scenes) {
      json document = filum::readJsonFile(path.string());
      document["duration"] = std::min(document.value("duration", 1.0), duration);
      const std::string integrator = document["integrator"].value("type", "RungeKutta4");
      printRow(csv, path.stem().string(), -1, integrator, measure(document, path.string(), repetitions));
    }
  }
  std::fclose(csv);
#ifdef FILUM_PEER_BULLET
  // The peers append their rows to the same CSV (built with -DFILUM_WITH_PEERS=ON).
  std::printf("peers (same rope, same machine, same run)\n");
  std::fflush(stdout);
  for (int n : sizes)
    for (int iterations : {4, 64}) {
      const std::string command = std::string(FILUM_PEER_BULLET) + " --nodes " + std::to_string(n) + " --iterations " +
                                  std::to_string(iterations) + " --repetitions " + std::to_string(repetitions) +
                                  " --duration " + std::to_string(duration) + " --csv " + csv_path;
      if (std::system(command.c_str()) != 0) std::fprintf(stderr, "warning: %s failed\n", command.c_str());
    }
#endif
#ifdef FILUM_PEER_MUJOCO
  // MuJoCo 2.2 factors the chain's dense joint-space mass matrix: O(n³), 28 ms per simulated ms
  // at 165 bodies already; 1000 would take hours.
  for (int n : sizes) {
    if (n > 165) continue;
    const std::string command = std::string(FILUM_PEER_MUJOCO) + " --bodies " + std::to_string(n) + " --repetitions " +
                                std::to_string(repetitions) + " --duration " + std::to_string(duration) + " --csv " + csv_path;
    if (std::system(command.c_str()) != 0) std::fprintf(stderr, "warning: %s failed\n", command.c_str());
  }
#endif
  std::printf("wrote %s\n", csv_path.c_str());
  if (plot) {
    const std::string command = "/usr/bin/python3 " + std::string(FILUM_SOURCE_DIR) + "/apps/tools/plot_realtime.py " + out;
    return std::system(command.c_str()) == 0 ? 0 : 4;
  }
  return 0;
}
