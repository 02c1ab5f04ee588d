// accuracy_pareto: run time against error. For each reference problem with an
// analytic solution (apps/validation: catenary, taut string, cantilever), each integrator, time
// step and number of control points: the error against the analytic solution and the wall time
// per simulated second. Writes pareto_<problem>.csv and, through apps/tools/plot_pareto.py
// (Debian python3-matplotlib), pareto_<problem>.png: log-log error against cost, one colour per
// integrator, one marker per n, the Pareto front (no run both cheaper and more accurate) drawn.
// Implicit schemes twice: "ImplicitEuler" / "ImplicitMidpoint" are the linearized default with its
// error estimate, ".../newton" the same schemes solved by Newton.
//
//   build/apps/bench/accuracy_pareto [--quick] [--out DIR] [--no-plot] [--problem NAME]
//
// One configuration at a time, for sweeps that spread the runs over processes or machines
// (python/filum_sweeps): --list prints the configurations (index, problem, integrator,
// dt, n) in the order of the serial run; --configuration K runs configuration K alone and prints
// its result row (full precision); --rows FILE takes such rows instead of running, and writes the
// same CSV, report and plot as a serial run.
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
#include <optional>
#include <string>
#include <vector>

#include "bench/indexed_rows.hpp"
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

/// One run of the study: a problem, an integrator, a number of control points and a step.
struct Configuration {
  const ReferenceProblem* problem;
  const Grid* grid;
  std::string integrator;
  int n;
  double dt;
};

/// Every configuration, in the order of the serial run: problem, integrator, n, dt.
std::vector<Configuration> listConfigurations(
    const std::vector<std::pair<std::unique_ptr<ReferenceProblem>, Grid>>& problems,
    const std::vector<std::string>& integrators, const std::string& only) {
  std::vector<Configuration> out;
  for (const auto& [problem, grid] : problems) {
    if (!only.empty() && problem->name() != only) continue;
    for (const std::string& type : integrators)
      for (int n : grid.control_points) {
        if (!isImplicit(type) && n > grid.explicit_max_points) continue;
        for (double dt : isImplicit(type) ? grid.implicit_dt : grid.explicit_dt)
          out.push_back({problem.get(), &grid, type, n, dt});
      }
  }
  return out;
}

RunResult runConfiguration(const Configuration& c, bool quick) {
  RunSettings settings;
  settings.integrator = integratorFor(c.integrator);
  settings.dt = c.dt;
  settings.control_points = c.n;
  settings.wall_budget = quick ? 0.0 : kWallBudget;
  return filum::validation::runProblem(*c.problem, settings);
}

/// "K,stable,error,wall_seconds,simulated,steps,over_budget" at full precision (%.17g: read back
/// bit for bit, so the front of gathered rows is the serial run's).
void printResultRow(std::FILE* out, std::size_t index, const RunResult& r) {
  std::fprintf(out, "%zu,%d,%.17g,%.17g,%.17g,%ld,%d\n", index, r.stable ? 1 : 0, r.error, r.wall_seconds, r.simulated,
               r.steps, r.over_budget ? 1 : 0);
}

/// Reads printResultRow lines (any order) into results[K]; a missing or malformed row is an error
/// naming the file and line.
bool readResultRows(const std::string& path, std::vector<std::optional<RunResult>>& results) {
  const auto parse = [](const std::string& line, std::size_t& index, RunResult& r) {
    int stable = 0, over_budget = 0;
    char tail;
    if (std::sscanf(line.c_str(), "%zu,%d,%lf,%lf,%lf,%ld,%d%c", &index, &stable, &r.error, &r.wall_seconds,
                    &r.simulated, &r.steps, &over_budget, &tail) != 7)
      return false;
    r.stable = stable != 0;
    r.over_budget = over_budget != 0;
    return true;
  };
  return filum::bench::readIndexedRows(path, results, parse, "K,stable,error,wall_s,simulated_s,steps,over_budget",
                                       "accuracy_pareto");
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, plot = true, list = false;
  std::string out = "out/accuracy_pareto", only, rows_file;  // not "." : a run from the checkout left CSVs at its root
  long configuration = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") quick = true;
    else if (a == "--no-plot") plot = false;
    else if (a == "--out" && i + 1 < argc) out = argv[++i];
    else if (a == "--problem" && i + 1 < argc) only = argv[++i];
    else if (a == "--list") list = true;
    else if (a == "--configuration" && i + 1 < argc) configuration = std::strtol(argv[++i], nullptr, 10);
    else if (a == "--rows" && i + 1 < argc) rows_file = argv[++i];
    else {
      std::cerr << "usage: accuracy_pareto [--quick] [--out DIR] [--no-plot] [--problem catenary|taut_string|cantilever]\n"
                   "                       [--list | --configuration K | --rows FILE]\n";
      return 2;
    }
  }
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

  const std::vector<Configuration> configurations = listConfigurations(problems, integrators, only);

  // One configuration at a time (sweeps): the list, or one run's result row.
  if (list) {
    for (std::size_t k = 0; k < configurations.size(); ++k) {
      const Configuration& c = configurations[k];
      std::printf("%zu,%s,%s,%.17g,%d\n", k, c.problem->name().c_str(), c.integrator.c_str(), c.dt, c.n);
    }
    return 0;
  }
  if (configuration >= 0) {
    if (configuration >= static_cast<long>(configurations.size())) {
      std::cerr << "--configuration " << configuration << ": expected an index below " << configurations.size()
                << " (accuracy_pareto --list)\n";
      return 2;
    }
    printResultRow(stdout, configuration, runConfiguration(configurations[configuration], quick));
    return 0;
  }
  // Every result: gathered by a sweep (--rows), or run here one after the other.
  std::vector<std::optional<RunResult>> results(configurations.size());
  if (!rows_file.empty() && !readResultRows(rows_file, results)) return 1;
  std::filesystem::create_directories(out);

  std::size_t next = 0;  // configurations are grouped by problem, in the order of `problems`
  for (auto& [problem, grid] : problems) {
    if (!only.empty() && problem->name() != only) continue;
    std::printf("== %s: %s, %.4g s simulated per run\n", problem->name().c_str(), problem->errorMeaning().c_str(),
                problem->duration());
    std::vector<Row> rows;
    for (; next < configurations.size() && configurations[next].problem == problem.get(); ++next) {
      const Configuration& c = configurations[next];
      if (!results[next]) results[next] = runConfiguration(c, quick);
      Row row{c.integrator, c.dt, c.n, *results[next]};
      std::printf("  %-23s n = %2d dt = %.2e: %s error %.3e, %.3e s wall per simulated s\n", c.integrator.c_str(), c.n,
                  c.dt, row.result.over_budget ? "TOO SLOW" : row.result.stable ? "        " : "UNSTABLE",
                  row.result.error, row.result.wallPerSimulatedSecond());
      std::fflush(stdout);
      rows.push_back(std::move(row));
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
