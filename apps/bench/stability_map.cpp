// stability_map: the largest stable time step of every integrator as the thread's stiffness grows.
// For each Young's modulus E and each integrator, bisection on log dt over
// [1e-9, 1e-1] s of runs of 2000 steps of apps/validation/stability.hpp's problem (a 10 cm thread,
// 20 control points, Green-Lagrange stretching and quadratic bending of modulus E, one end fixed,
// released under gravity, viscous γ = 1/s); unstable = a failed step (non-finite, faster than
// max_speed, Newton failing after halving) or the energy rising by more than 5 % of m g L.
// Writes stability_map.csv (integrator, E, ω_max, largest stable dt, ω_max·dt, capped) and, with
// apps/tools/plot_stability.py and Debian's python3-matplotlib, stability_map.png.
//
//   build/apps/bench/stability_map [--quick] [--out DIR] [--no-plot]
//
// --quick: three moduli, 500-step runs, 8 bisections (a few seconds; the test suite's short form
// is tests/mechanics/stability_map_test.cpp).
//
// One configuration (a modulus and an integrator) at a time, for sweeps that spread the runs over
// processes or machines (python/filum_sweeps): --list prints the configurations (index,
// integrator, E) in the order of the CSV; --configuration K runs configuration K alone and prints
// its result row (K, ω_max, largest stable dt at full precision); --rows FILE takes such rows
// instead of running and writes the same CSV and plot as a serial run.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "bench/indexed_rows.hpp"
#include "validation/stability.hpp"

namespace {

constexpr double kDtMin = 1e-9, kDtMax = 1e-1;  // s, the bisection's bracket

struct Configuration {
  std::string integrator;
  double youngs_modulus;  // E (Pa)
};

struct Result {
  double omega = 0.0;  // ω_max (rad/s)
  double dt = 0.0;     // largest stable step (s)
};

/// Moduli outer, integrators inner: the order of the CSV.
std::vector<Configuration> listConfigurations(bool quick) {
  const std::vector<double> moduli = quick ? std::vector<double>{1e6, 1e8, 2e9}
                                           : std::vector<double>{1e5, 1e6, 1e7, 1e8, 1e9, 2e9, 1e10};
  const std::vector<std::string> integrators = {"ExplicitEuler", "SymplecticEuler", "RungeKutta4", "ImplicitEuler",
                                                "ImplicitMidpoint"};
  std::vector<Configuration> out;
  for (double E : moduli)
    for (const std::string& type : integrators) out.push_back({type, E});
  return out;
}

Result runConfiguration(const Configuration& c, bool quick) {
  filum::validation::StabilityProblem problem;
  problem.steps = quick ? 500 : 2000;
  problem.youngs_modulus = c.youngs_modulus;
  const int bisections = quick ? 8 : 14;
  Result r;
  r.omega = filum::validation::stiffestFrequency(problem);
  r.dt = filum::validation::largestStableStep({{"type", c.integrator}}, problem, kDtMin, kDtMax, bisections);
  return r;
}

/// Reads "K,omega,dt" rows (any order; %.17g reads back bit for bit) into results[K]; a missing or
/// malformed row is an error naming the file and line.
bool readResultRows(const std::string& path, std::vector<std::optional<Result>>& results) {
  const auto parse = [](const std::string& line, std::size_t& index, Result& r) {
    char tail;
    return std::sscanf(line.c_str(), "%zu,%lf,%lf%c", &index, &r.omega, &r.dt, &tail) == 3;
  };
  return filum::bench::readIndexedRows(path, results, parse, "K,omega_max,largest_stable_dt", "stability_map");
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, plot = true, list = false;
  std::string out = "out/stability_map", rows_file;  // not "." (files at the checkout root)
  long configuration = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") quick = true;
    else if (a == "--no-plot") plot = false;
    else if (a == "--out" && i + 1 < argc) out = argv[++i];
    else if (a == "--list") list = true;
    else if (a == "--configuration" && i + 1 < argc) configuration = std::strtol(argv[++i], nullptr, 10);
    else if (a == "--rows" && i + 1 < argc) rows_file = argv[++i];
    else {
      std::cerr << "usage: stability_map [--quick] [--out DIR] [--no-plot] [--list | --configuration K | --rows FILE]\n";
      return 2;
    }
  }
  const std::vector<Configuration> configurations = listConfigurations(quick);

  // One configuration at a time (sweeps): the list, or one run's result row.
  if (list) {
    for (std::size_t k = 0; k < configurations.size(); ++k)
      std::printf("%zu,%s,%.17g\n", k, configurations[k].integrator.c_str(), configurations[k].youngs_modulus);
    return 0;
  }
  if (configuration >= 0) {
    if (configuration >= static_cast<long>(configurations.size())) {
      std::cerr << "--configuration " << configuration << ": expected an index below " << configurations.size()
                << " (stability_map --list)\n";
      return 2;
    }
    const Result r = runConfiguration(configurations[configuration], quick);
    std::printf("%ld,%.17g,%.17g\n", configuration, r.omega, r.dt);
    return 0;
  }
  // Every result: gathered by a sweep (--rows), or run here one after the other.
  std::vector<std::optional<Result>> results(configurations.size());
  if (!rows_file.empty() && !readResultRows(rows_file, results)) return 1;

  std::filesystem::create_directories(out);
  const std::string csv_path = out + "/stability_map.csv";
  std::ofstream csv(csv_path);
  csv << "integrator,youngs_modulus,omega_max,largest_stable_dt,omega_dt,capped\n";
  std::printf("%-17s %10s %12s %16s %10s\n", "integrator", "E (Pa)", "omega_max", "largest dt (s)", "omega*dt");
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < configurations.size(); ++k) {
    const Configuration& c = configurations[k];
    if (!results[k]) results[k] = runConfiguration(c, quick);
    const double omega = results[k]->omega, dt = results[k]->dt;
    const bool capped = dt >= kDtMax;
    std::printf("%-17s %10.1e %12.4e %16.4e %10.3f%s\n", c.integrator.c_str(), c.youngs_modulus, omega, dt, omega * dt,
                capped ? "  (stable at the largest step tried)" : "");
    csv << c.integrator << ',' << c.youngs_modulus << ',' << omega << ',' << dt << ',' << omega * dt << ','
        << (capped ? 1 : 0) << '\n';
    std::fflush(stdout);
  }
  csv.close();
  std::printf("wrote %s (%.1f s)\n", csv_path.c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  if (plot) {
    const std::string command = "/usr/bin/python3 " FILUM_SOURCE_DIR "/apps/tools/plot_stability.py " + csv_path;
    if (std::system(command.c_str()) != 0) std::cerr << "plot failed: " << command << '\n';
  }
  return 0;
}
