// mujoco_rope: the benchmark rope of bench_realtime (1 m, 0.1 kg, radius 5 mm, one end held,
// released horizontally, dt = 1 ms) in MuJoCo 2.2: its composite "rope", N capsules joined by
// two hinges each, the first one fixed to the world; the implicit integrator (implicit in the
// joints' small damping, 1e-5 N·m·s).
// Generalized coordinates make the links exactly inextensible, so the strain is 0 by
// construction; bending and twisting are free (no joint stiffness), like the thread's negligible
// bending at E = 1e8 Pa over 1 m. Built only with -DFILUM_WITH_PEERS=ON (Debian's
// libmujoco-dev); bench_realtime runs it when present.
//
// Prints the row bench_realtime prints and appends it to --csv: wall time per simulated ms
// (mj_step only, median of --repetitions runs), 0 strain, and the drift of MuJoCo's energy
// (kinetic + gravitational) relative to m g ℓ.
//   mujoco_rope --bodies 165 [--duration 10] [--repetitions 5] [--csv FILE]
#include <mujoco/mujoco.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

constexpr double kLength = 1.0, kMass = 0.1, kRadius = 0.005, kGravity = 9.81, kDt = 1e-3;

/// MJCF of the rope: MuJoCo 2.2's composite "rope" of `bodies` capsules (two hinges between
/// neighbours), its root body RB0 fixed to the world at the origin — the held end.
std::string ropeModel(int bodies) {
  const double h = kLength / bodies, m = kMass / bodies;
  char xml[1024];
  std::snprintf(xml, sizeof xml,
                "<mujoco><option timestep=\"%g\" gravity=\"0 0 %g\" integrator=\"implicit\"><flag energy=\"enable\"/>"
                "</option><worldbody><body name=\"RB0\" pos=\"0 0 0\">"
                "<composite type=\"rope\" count=\"%d 1 1\" spacing=\"%g\" offset=\"0 0 0\" prefix=\"R\">"
                "<joint kind=\"main\" damping=\"1e-5\"/>"
                "<geom type=\"capsule\" size=\"%g %g\" mass=\"%g\" contype=\"0\" conaffinity=\"0\"/>"
                "</composite></body></worldbody></mujoco>",
                kDt, -kGravity, bodies, h, kRadius, 0.5 * h, m);
  return xml;
}

double runOnce(const mjModel* model, double duration, double* drift) {
  mjData* data = mj_makeData(model);
  mj_forward(model, data);
  const double e0 = data->energy[0] + data->energy[1];
  const long steps = std::lround(duration / kDt);
  double wall = 0.0;
  for (long k = 0; k < steps; ++k) {
    const auto start = std::chrono::steady_clock::now();
    mj_step(model, data);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  mj_forward(model, data);
  *drift = (data->energy[0] + data->energy[1] - e0) / (kMass * kGravity * kLength);
  const bool finite = std::isfinite(data->energy[0] + data->energy[1]);
  mj_deleteData(data);
  return finite ? 1e3 * wall / (1e3 * duration) : -1.0;
}

}  // namespace

int main(int argc, char** argv) {
  int bodies = 165, repetitions = 5;
  double duration = 10.0;
  std::string csv;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 < argc && arg == "--bodies") bodies = std::atoi(argv[++i]);
    else if (i + 1 < argc && arg == "--repetitions") repetitions = std::atoi(argv[++i]);
    else if (i + 1 < argc && arg == "--duration") duration = std::atof(argv[++i]);
    else if (i + 1 < argc && arg == "--csv") csv = argv[++i];
    else {
      std::fprintf(stderr, "usage: mujoco_rope [--bodies N] [--repetitions R] [--duration T] [--csv FILE]\n");
      return arg == "--help" ? 0 : 2;
    }
  }
  if (bodies < 2 || bodies > 2000 || repetitions < 1 || !(duration > 0.0) || duration > 1e4) {
    std::fprintf(stderr, "error: expected 2 <= bodies <= 2000, repetitions >= 1, 0 < duration <= 1e4\n");
    return 2;
  }
  const std::string xml = ropeModel(bodies);
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  mj_makeEmptyFileVFS(&vfs, "rope.xml", static_cast<int>(xml.size()));
  std::copy(xml.begin(), xml.end(), static_cast<char*>(vfs.filedata[vfs.nfile - 1]));
  char error[1000] = "";
  mjModel* model = mj_loadXML("rope.xml", &vfs, error, sizeof error);
  mj_deleteVFS(&vfs);
  if (!model) {
    std::fprintf(stderr, "error: MuJoCo refused the rope model: %s\n", error);
    return 3;
  }
  std::vector<double> walls;
  double drift = 0.0, first_drift = 0.0;
  for (int r = 0; r < repetitions; ++r) {
    walls.push_back(runOnce(model, duration, &drift));
    if (r == 0) first_drift = drift;
  }
  mj_deleteModel(model);
  std::sort(walls.begin(), walls.end());
  const double median = walls[walls.size() / 2];
  if (median < 0.0) {
    std::printf("%-22s %5d  %-26s FAILED: non-finite energy (diverged)\n", "rope", bodies, "MuJoCo rope");
    return 3;
  }
  std::printf("%-22s %5d  %-26s dt %-8.2g %9.4f ms/ms  strain %.2e  drift %+.2e\n", "rope", bodies, "MuJoCo rope", kDt,
              median, 0.0, first_drift);
  if (!csv.empty()) {
    std::FILE* f = std::fopen(csv.c_str(), "a");
    if (!f) {
      std::fprintf(stderr, "error: cannot append to %s\n", csv.c_str());
      return 4;
    }
    std::fprintf(f, "rope,%d,MuJoCo rope,%g,%g,%.6g,0,%.6g,,,,ok\n", bodies, kDt, duration, median, first_drift);
    std::fclose(f);
  }
  return 0;
}
