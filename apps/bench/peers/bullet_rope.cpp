// bullet_rope: the benchmark rope of bench_realtime (1 m, 0.1 kg, one end held, released
// horizontally, dt = 1 ms) in Bullet's position-based soft body (btSoftBody: mass points joined
// by links, constraints projected by `piterations` Gauss-Seidel sweeps per step), to put filum's
// figures beside a peer's measured in the same run. Built only with -DFILUM_WITH_PEERS=ON
// (Debian's libbullet-dev); bench_realtime runs it when present.
//
// Prints the rows bench_realtime prints and appends them to --csv: wall time per simulated ms
// (stepSimulation only, median of --repetitions runs), the largest strain over the run (link
// length / rest length − 1, sampled every 10 ms) and the drift of kinetic + gravitational
// energy relative to m g ℓ (Bullet's links store no elastic energy to add).
//   bullet_rope --nodes 165 --iterations 64 [--duration 10] [--repetitions 5] [--csv FILE]
#include <btBulletDynamicsCommon.h>

#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace {

struct Run {
  double wall_ms_per_sim_ms = 0.0;
  double max_strain = 0.0;
  double energy_drift = 0.0;
};

constexpr double kLength = 1.0, kMass = 0.1, kGravity = 9.81, kDt = 1e-3;

double mechanicalEnergy(const btSoftBody& body) {
  double e = 0.0;
  for (int i = 0; i < body.m_nodes.size(); ++i) {
    const btSoftBody::Node& n = body.m_nodes[i];
    if (n.m_im <= 0) continue;  // the held end
    const double m = 1.0 / n.m_im;
    e += 0.5 * m * n.m_v.length2() + m * kGravity * n.m_x.z();
  }
  return e;
}

double maxStrain(const btSoftBody& body, double rest) {
  double strain = 0.0;
  for (int i = 0; i < body.m_links.size(); ++i) {
    const btSoftBody::Link& l = body.m_links[i];
    strain = std::max(strain, std::abs((l.m_n[1]->m_x - l.m_n[0]->m_x).length() / rest - 1.0));
  }
  return strain;
}

Run runOnce(int nodes, int iterations, double duration) {
  btSoftBodyRigidBodyCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
  world.setGravity(btVector3(0, 0, -kGravity));
  btSoftBodyWorldInfo& info = world.getWorldInfo();
  info.m_gravity = btVector3(0, 0, -kGravity);
  info.m_sparsesdf.Initialize();

  // CreateRope(from, to, res, fixeds) makes res + 2 nodes; bit 1 of fixeds holds the first.
  btSoftBody* rope = btSoftBodyHelpers::CreateRope(info, btVector3(0, 0, 0), btVector3(kLength, 0, 0), nodes - 2, 1);
  rope->m_cfg.piterations = iterations;
  rope->m_materials[0]->m_kLST = 1.0;  // links as stiff as the solver makes them
  rope->setTotalMass(kMass);
  world.addSoftBody(rope);

  const double rest = kLength / (nodes - 1);
  const long steps = std::lround(duration / kDt);
  const long sample_every = std::lround(0.01 / kDt);
  const double e0 = mechanicalEnergy(*rope);
  Run run;
  double wall = 0.0;
  for (long k = 0; k < steps; ++k) {
    const auto start = std::chrono::steady_clock::now();
    world.stepSimulation(kDt, 1, kDt);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (k % sample_every == 0) run.max_strain = std::max(run.max_strain, maxStrain(*rope, rest));
  }
  run.max_strain = std::max(run.max_strain, maxStrain(*rope, rest));
  run.energy_drift = (mechanicalEnergy(*rope) - e0) / (kMass * kGravity * kLength);
  run.wall_ms_per_sim_ms = 1e3 * wall / (1e3 * duration);
  world.removeSoftBody(rope);
  delete rope;
  return run;
}

}  // namespace

int main(int argc, char** argv) {
  int nodes = 165, iterations = 64, repetitions = 5;
  double duration = 10.0;
  std::string csv;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* what) -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "error: %s needs a value (%s)\n", arg.c_str(), what);
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--nodes") nodes = std::atoi(value("node count >= 3").c_str());
    else if (arg == "--iterations") iterations = std::atoi(value("solver iterations >= 1").c_str());
    else if (arg == "--repetitions") repetitions = std::atoi(value("runs >= 1").c_str());
    else if (arg == "--duration") duration = std::atof(value("simulated seconds > 0").c_str());
    else if (arg == "--csv") csv = value("a CSV file to append to");
    else {
      std::fprintf(stderr, "usage: bullet_rope [--nodes N] [--iterations I] [--repetitions R] [--duration T] [--csv FILE]\n");
      return arg == "--help" ? 0 : 2;
    }
  }
  if (nodes < 3 || nodes > 100000 || iterations < 1 || iterations > 10000 || repetitions < 1 || !(duration > 0.0) ||
      duration > 1e4) {
    std::fprintf(stderr, "error: expected 3 <= nodes <= 1e5, 1 <= iterations <= 1e4, repetitions >= 1, 0 < duration <= 1e4\n");
    return 2;
  }
  std::vector<Run> runs;
  for (int r = 0; r < repetitions; ++r) runs.push_back(runOnce(nodes, iterations, duration));
  std::vector<double> walls;
  for (const Run& r : runs) walls.push_back(r.wall_ms_per_sim_ms);
  std::sort(walls.begin(), walls.end());
  const Run& first = runs.front();
  const std::string scheme = "Bullet " + std::to_string(iterations) + " it.";
  std::printf("%-22s %5d  %-26s dt %-8.2g %9.4f ms/ms  strain %.2e  drift %+.2e\n", "rope", nodes, scheme.c_str(), kDt,
              walls[walls.size() / 2], first.max_strain, first.energy_drift);
  if (!csv.empty()) {
    std::FILE* f = std::fopen(csv.c_str(), "a");
    if (!f) {
      std::fprintf(stderr, "error: cannot append to %s\n", csv.c_str());
      return 4;
    }
    std::fprintf(f, "rope,%d,%s,%g,%g,%.6g,%.6g,%.6g,,,,ok\n", nodes, scheme.c_str(), kDt, duration, walls[walls.size() / 2],
                 first.max_strain, first.energy_drift);
    std::fclose(f);
  }
  return 0;
}
