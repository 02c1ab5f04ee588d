// accuracy_pareto: run time against error (issue 4, item 4). For each reference problem with an
// analytic solution (apps/validation: catenary, taut string, cantilever), each integrator, time
// step and number of control points: the error against the analytic solution and the wall time
// per simulated second. Writes pareto_<problem>.csv and, through apps/tools/plot_pareto.py
// (Debian python3-matplotlib), pareto_<problem>.png: log-log error against cost, one colour per
// integrator, one marker per n, the Pareto front (no run both cheaper and more accurate) drawn.
// Implicit schemes twice: "ImplicitEuler" / "ImplicitMidpoint" are the linearized default with its
// error estimate, ".../newton" the same schemes solved by Newton (issue 12).
//
//   build-mech/apps/bench/accuracy_pareto [--quick] [--out DIR] [--no-plot] [--problem NAME]
//
// Errors (see each problem's header): catenary — max distance to the catenary after 1 s of
// damped settling (m; includes what has not settled yet); taut string — max |y − y_exact| over
// two periods of mode 1, relative to the amplitude; cantilever — max |w_tip − w_exact| over one
// period of mode 1, relative to the static deflection. Unstable runs (a failed step) are listed
// with error inf and left off the front; so are runs stopped after the wall-time budget of a run
// (kWallBudget, full grid only: a run that needs more is far from the front, whose points take
// a few seconds at most, and an implicit scheme halving its step through a failing Newton iteration
// would otherwise take minutes per configuration). Wall time counts the steps only (no error evaluation,
// no scene loading), single thread.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "validation/cantilever.hpp"
#include "validation/catenary.hpp"
#include "validation/taut_string.hpp"

namespace {

using filum::validation::ReferenceProblem;
using filum::validation::RunResult;
using filum::validation::RunSettings;
constexpr double kWallBudget = 20.0;  // s of wall time per run (full grid)
constexpr double kTie = 1e-3;         // relative error gain that puts a run on the Pareto front

struct Grid {
  std::vector<int> control_points;
  std::vector<double> implicit_dt;       // ImplicitEuler, ImplicitMidpoint
  std::vector<double> explicit_dt;       // ExplicitEuler, SymplecticEuler, RungeKutta4
  int explicit_max_points;               // explicit runs only up to this n (cost)
  double target;                         // "accurate enough" error for the report
};

struct Row {
  std::string integrator;
  double dt;
  int n;
  RunResult result;
  bool pareto = false;
};

bool isImplicit(const std::string& type) { return type.rfind("Implicit", 0) == 0; }

/// The integrator block of a label: "ImplicitEuler" is the default (linearized, with its error
/// estimate), "ImplicitEuler/newton" the same scheme solved by Newton to its tolerance.
nlohmann::json integratorFor(const std::string& label) {
  const auto slash = label.find('/');
  if (slash == std::string::npos) return {{"type", label}};
  return {{"type", label.substr(0, slash)}, {"solve", label.substr(slash + 1)}};
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, plot = true;
  std::string out = ".", only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") quick = true;
    else if (a == "--no-plot") plot = false;
    else if (a == "--out" && i + 1 < argc) out = argv[++i];
    else if (a == "--problem" && i + 1 < argc) only = argv[++i];
    else {
      std::cerr << "usage: accuracy_pareto [--quick] [--out DIR] [--no-plot] [--problem catenary|taut_string|cantilever]\n";
      return 2;
    }
  }
  std::filesystem::create_directories(out);

  filum::validation::Catenary::Options catenary_options;
  catenary_options.duration = 1.0;
  std::vector<std::pair<std::unique_ptr<ReferenceProblem>, Grid>> problems;
  problems.emplace_back(std::make_unique<filum::validation::Catenary>(catenary_options),
                        quick ? Grid{{10, 30}, {1e-2, 2e-3}, {1e-6}, 10, 1e-4}
                              : Grid{{10, 20, 30, 40, 60}, {2e-2, 1e-2, 5e-3, 2e-3, 1e-3, 1e-4, 2e-5}, {1e-6}, 30, 1e-4});
  problems.emplace_back(std::make_unique<filum::validation::TautString>(),
                        quick ? Grid{{10, 30}, {2e-5, 5e-6}, {5e-7, 2.5e-7}, 30, 1e-2}
                              : Grid{{10, 20, 30, 40, 60}, {1e-4, 5e-5, 2e-5, 1e-5, 5e-6, 2e-6, 1e-6},
                                     {1e-6, 5e-7, 2.5e-7, 1.25e-7}, 60, 1e-2});
  problems.emplace_back(std::make_unique<filum::validation::Cantilever>(),
                        quick ? Grid{{10, 30}, {5e-4, 1e-4}, {5e-7}, 30, 1e-2}
                              : Grid{{10, 20, 30, 40, 60}, {1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5},
                                     {1e-6, 5e-7, 2.5e-7}, 60, 1e-2});
  const std::vector<std::string> integrators = {"ExplicitEuler",        "SymplecticEuler",  "RungeKutta4",
                                                "ImplicitEuler",        "ImplicitMidpoint", "ImplicitEuler/newton",
                                                "ImplicitMidpoint/newton"};

  for (auto& [problem, grid] : problems) {
    if (!only.empty() && problem->name() != only) continue;
    std::printf("== %s: %s, %.4g s simulated per run\n", problem->name().c_str(), problem->errorMeaning().c_str(),
                problem->duration());
    std::vector<Row> rows;
    for (const std::string& type : integrators)
      for (int n : grid.control_points) {
        if (!isImplicit(type) && n > grid.explicit_max_points) continue;
        for (double dt : isImplicit(type) ? grid.implicit_dt : grid.explicit_dt) {
          RunSettings settings;
          settings.integrator = integratorFor(type);
          settings.dt = dt;
          settings.control_points = n;
          settings.wall_budget = quick ? 0.0 : kWallBudget;
          Row row{type, dt, n, filum::validation::runProblem(*problem, settings)};
          std::printf("  %-23s n = %2d dt = %.2e: %s error %.3e, %.3e s wall per simulated s\n", type.c_str(), n, dt,
                      row.result.over_budget ? "TOO SLOW" : row.result.stable ? "        " : "UNSTABLE",
                      row.result.error, row.result.wallPerSimulatedSecond());
          std::fflush(stdout);
          rows.push_back(std::move(row));
        }
      }

    // Pareto front: in order of cost, a run is on the front when it is more accurate than every
    // cheaper run — by more than kTie relative: runs that reach the same static solution (the
    // catenary at rest with another dt) differ in the last digits only and are ties, not gains.
    std::vector<Row*> order;
    for (Row& r : rows)
      if (r.result.stable) order.push_back(&r);
    std::sort(order.begin(), order.end(), [](const Row* a, const Row* b) {
      return a->result.wallPerSimulatedSecond() < b->result.wallPerSimulatedSecond();
    });
    double best = std::numeric_limits<double>::infinity();
    for (Row* r : order)
      if (r->result.error < (1.0 - kTie) * best) {
        best = r->result.error;
        r->pareto = true;
      }

    const std::string csv_path = out + "/pareto_" + problem->name() + ".csv";
    std::ofstream csv(csv_path);
    csv << "# " << problem->name() << ": error = " << problem->errorMeaning() << "\n";
    csv << "problem,integrator,dt,control_points,stable,error,wall_s,simulated_s,wall_per_sim_s,steps,pareto,over_budget\n";
    for (const Row& r : rows)
      csv << problem->name() << ',' << r.integrator << ',' << r.dt << ',' << r.n << ',' << (r.result.stable ? 1 : 0) << ','
          << r.result.error << ',' << r.result.wall_seconds << ',' << r.result.simulated << ','
          << r.result.wallPerSimulatedSecond() << ',' << r.result.steps << ',' << (r.pareto ? 1 : 0) << ','
          << (r.result.over_budget ? 1 : 0) << '\n';
    csv.close();

    // Report: the front, its most accurate point, and the cheapest point meeting the target.
    std::printf("  Pareto front (%s):\n", problem->name().c_str());
    const Row *most_accurate = nullptr, *cheapest_on_target = nullptr;
    for (const Row* r : order) {
      if (!r->pareto) continue;
      std::printf("    %-16s n = %2d dt = %.2e  error %.3e  %.3e s/s\n", r->integrator.c_str(), r->n, r->dt, r->result.error,
                  r->result.wallPerSimulatedSecond());
      most_accurate = r;
      if (!cheapest_on_target && r->result.error <= grid.target) cheapest_on_target = r;
    }
    if (most_accurate)
      std::printf("  most accurate: %s n = %d dt = %.2e, error %.3e at %.3e s wall per simulated s\n",
                  most_accurate->integrator.c_str(), most_accurate->n, most_accurate->dt, most_accurate->result.error,
                  most_accurate->result.wallPerSimulatedSecond());
    if (cheapest_on_target)
      std::printf("  cheapest with error <= %.0e: %s n = %d dt = %.2e, error %.3e at %.3e s wall per simulated s\n",
                  grid.target, cheapest_on_target->integrator.c_str(), cheapest_on_target->n, cheapest_on_target->dt,
                  cheapest_on_target->result.error, cheapest_on_target->result.wallPerSimulatedSecond());
    std::printf("  wrote %s\n", csv_path.c_str());
    if (plot) {
      const std::string command = "/usr/bin/python3 " FILUM_SOURCE_DIR "/apps/tools/plot_pareto.py " + csv_path;
      if (std::system(command.c_str()) != 0) std::cerr << "plot failed: " << command << '\n';
    }
  }
  return 0;
}
