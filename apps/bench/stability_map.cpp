// stability_map: the largest stable time step of every integrator as the thread's stiffness grows
// (issue 4, item 5). For each Young's modulus E and each integrator, bisection on log dt over
// [1e-9, 1e-1] s of runs of 2000 steps of apps/validation/stability.hpp's problem (a 10 cm thread,
// 20 control points, Green-Lagrange stretching and quadratic bending of modulus E, one end fixed,
// released under gravity, viscous γ = 1/s); unstable = a failed step (non-finite, faster than
// max_speed, Newton failing after halving) or the energy rising by more than 5 % of m g L.
// Writes stability_map.csv (integrator, E, ω_max, largest stable dt, ω_max·dt, capped) and, with
// apps/tools/plot_stability.py and Debian's python3-matplotlib, stability_map.png.
//
//   build-mech/apps/bench/stability_map [--quick] [--out DIR] [--no-plot]
//
// --quick: three moduli, 500-step runs, 8 bisections (a few seconds; the test suite's short form
// is tests/mechanics/stability_map_test.cpp).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "validation/stability.hpp"

int main(int argc, char** argv) {
  bool quick = false, plot = true;
  std::string out = ".";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") quick = true;
    else if (a == "--no-plot") plot = false;
    else if (a == "--out" && i + 1 < argc) out = argv[++i];
    else {
      std::cerr << "usage: stability_map [--quick] [--out DIR] [--no-plot]\n";
      return 2;
    }
  }
  std::filesystem::create_directories(out);
  const std::vector<double> moduli = quick ? std::vector<double>{1e6, 1e8, 2e9}
                                           : std::vector<double>{1e5, 1e6, 1e7, 1e8, 1e9, 2e9, 1e10};
  const std::vector<std::string> integrators = {"ExplicitEuler", "SymplecticEuler", "RungeKutta4", "ImplicitEuler",
                                                "ImplicitMidpoint"};
  const double dt_min = 1e-9, dt_max = 1e-1;
  filum::validation::StabilityProblem problem;
  problem.steps = quick ? 500 : 2000;
  const int bisections = quick ? 8 : 14;

  const std::string csv_path = out + "/stability_map.csv";
  std::ofstream csv(csv_path);
  csv << "integrator,youngs_modulus,omega_max,largest_stable_dt,omega_dt,capped\n";
  std::printf("%-17s %10s %12s %16s %10s\n", "integrator", "E (Pa)", "omega_max", "largest dt (s)", "omega*dt");
  const auto start = std::chrono::steady_clock::now();
  for (double E : moduli) {
    problem.youngs_modulus = E;
    const double omega = filum::validation::stiffestFrequency(problem);
    for (const std::string& type : integrators) {
      const double dt = filum::validation::largestStableStep({{"type", type}}, problem, dt_min, dt_max, bisections);
      const bool capped = dt >= dt_max;
      std::printf("%-17s %10.1e %12.4e %16.4e %10.3f%s\n", type.c_str(), E, omega, dt, omega * dt,
                  capped ? "  (stable at the largest step tried)" : "");
      csv << type << ',' << E << ',' << omega << ',' << dt << ',' << omega * dt << ',' << (capped ? 1 : 0) << '\n';
      std::fflush(stdout);
    }
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
