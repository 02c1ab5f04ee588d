// `filum check` refuses physics mistakes (apps/filum/physics_check.hpp): an explicit step beyond
// its stability limit — the scene's stiffest mode by power iteration, checked against a dense
// generalized eigensolver —, a scene that names no integrator and so runs RungeKutta4 at a step
// a stiff thread cannot take, and a radius larger than the thread is long.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "filum/all_components.hpp"
#include "filum/check_command.hpp"
#include "filum/core/jacobian_accumulator.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/physics_check.hpp"
#include "filum/run_command.hpp"

namespace filum::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// A 10 cm 3-0 polypropylene suture (r = 0.1 mm, E = 2 GPa, 910 kg/m³) of n points, held at one end.
json suture(const std::string& integrator, double dt, int n = 20, double radius = 1e-4) {
  const json components = json::array(
      {{{"type", "DynamicSpline"}, {"control_points", {{"from", {0, 0, 0}}, {"to", {0.1, 0, 0}}, {"count", n}}},
        {"radius", radius}, {"density", 910}},
       {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}},
       {{"type", "ParametricBending"}, {"youngs_modulus", 2e9}},
       {{"type", "FixedPointConstraint"}, {"abscissa", 0.0}}});
  json scene = {{"name", "suture"}, {"dt", dt}, {"gravity", {0, 0, -9.81}},
                {"nodes", json::array({{{"name", "thread"}, {"components", components}}})}};
  if (!integrator.empty()) scene["integrator"] = {{"type", integrator}};
  return scene;
}

std::string check(const json& document, const std::string& name, int& status) {
  const fs::path dir = fs::path(FILUM_BINARY_DIR) / "test_output" / "physics_check";
  fs::create_directories(dir);
  const fs::path scene = dir / (name + ".json");
  std::ofstream(scene) << document.dump(2);
  std::ostringstream out;
  status = checkScene(scene.string(), out);
  return out.str();
}

TEST(PhysicsCheck, TheStiffestModeAgreesWithADenseEigensolver) {
  auto scene = loadScene(suture("RungeKutta4", 1e-7), "suture", makeFactory());
  const double omega = stiffestFrequency(*scene);
  // Independently: the largest eigenvalue of −K x = λ M x, dense.
  Triplets kt, mt;
  TripletAccumulator k(kt), m(mt);
  scene->addForceJacobian(scene->state(), -1.0, 0.0, k);
  scene->addMassMatrix(1.0, m);
  const int n = 3 * scene->stepGroupCount();
  SparseMatrix K(n, n), M(n, n);
  K.setFromTriplets(kt.begin(), kt.end());
  M.setFromTriplets(mt.begin(), mt.end());
  const MatX Kd = MatX(K);
  const VecX eig = Eigen::GeneralizedSelfAdjointEigenSolver<MatX>(0.5 * (Kd + Kd.transpose()), MatX(M)).eigenvalues();
  const double exact = std::sqrt(eig.cwiseAbs().maxCoeff());
  // The Rayleigh quotient approaches ω_max² from below; after 200 iterations it is within 2 %
  // (ω within 1 %) for this spectrum — well inside the check's margin of 1.5.
  EXPECT_LE(omega, exact * (1 + 1e-12));
  EXPECT_GT(omega, 0.99 * exact) << "power iteration " << omega << ", dense " << exact;
}

TEST(PhysicsCheck, AnExplicitStepBeyondItsStabilityLimitIsRefused) {
  auto scene = loadScene(suture("RungeKutta4", 1e-7), "suture", makeFactory());
  const double limit = 2.0 * std::sqrt(2.0) / stiffestFrequency(*scene);
  int status = -1;
  std::string out = check(suture("RungeKutta4", 1.2 * limit), "rk4_within", status);
  EXPECT_EQ(status, 0) << out;  // inside the margin: not refused
  out = check(suture("RungeKutta4", 2.0 * limit), "rk4_beyond", status);
  EXPECT_EQ(status, kRunSceneError) << out;
  EXPECT_NE(out.find("rk4_beyond.json: /dt: expected a step within RungeKutta4's stability limit"), std::string::npos)
      << out;
  out = check(suture("ImplicitEuler", 1e-3), "implicit", status);
  EXPECT_EQ(status, 0) << out;  // A-stable
}

TEST(PhysicsCheck, ASceneWithoutIntegratorIsToldItRunsRungeKutta4) {
  int status = -1;
  const std::string out = check(suture("", 1e-3), "no_integrator", status);
  EXPECT_EQ(status, kRunSceneError) << out;
  EXPECT_NE(out.find("names no \"integrator\" and runs the default RungeKutta4"), std::string::npos) << out;
  EXPECT_NE(out.find("ImplicitEuler"), std::string::npos) << out;
}

TEST(PhysicsCheck, ARadiusLargerThanTheThreadIsRefused) {
  int status = -1;
  const std::string out = check(suture("ImplicitEuler", 1e-3, 20, 1.0), "metre_radius", status);
  EXPECT_EQ(status, kRunSceneError) << out;
  EXPECT_NE(out.find("/nodes/0/components/0/radius: expected a radius below half the body's length"), std::string::npos)
      << out;
}

}  // namespace
}  // namespace filum::app
