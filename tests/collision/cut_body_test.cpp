// A body cut between steps (Scene::cut, CurveBody::cut: the knot at s raised to multiplicity
// d + 1, [Lenoir talk 2008] "local C-1 continuity => cut"), with constraints and contacts attached, on the
// scene apps/scenes/cut_thread.json (10 cm of 3-0 polypropylene held at both ends, cut in the
// middle, implicit Euler at 1 ms).
//   - At the instant of the cut nothing moves: the curve, its velocity field and the energy are
//     those of before (knot insertion is exact), and the two new ends both sit at P(s).
//   - From then on the strands are two bodies in one: no mass entry, force or stiffness entry
//     joins a control point of one to a point of the other, and no collision chord spans the cut.
//   - The run goes on: each half swings down from its grasper (energy only leaves the system
//     until they touch the table: no driving, dissipative integrator and damping; it never falls
//     below the energy of the two halves hanging straight down) and comes to rest leaning on the
//     table, where the contacts hold points of one strand each.
// Tolerances are stated where they are used.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "collision_scenes.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/jacobian_accumulator.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::collision {
namespace {

const std::string kCutThread = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/cut_thread.json";

/// cut_thread.json without its scheduled cut (the tests cut it themselves), after `steps` steps.
std::unique_ptr<Scene> uncutThread(long steps) {
  nlohmann::json document = readJsonFile(kCutThread);
  document["nodes"][0]["components"][0].erase("cuts");
  auto scene = loadScene(document, "cut thread (not cut)", app::makeFactory());
  for (long k = 0; k < steps; ++k) {
    const StepReport report = scene->step();
    EXPECT_TRUE(report.ok) << report.message;
  }
  return scene;
}

CurveBody& threadOf(Scene& scene) { return *scene.bodies()[0]->curve(); }

/// Index a of the first control point of the second strand: the first point of the row at the
/// cut from the right.
int secondStrandStart(const CurveBody& body) {
  BasisRow row;
  body.basis().evaluate(body.basis().cuts().at(0), row);
  return row.first;
}

TEST(CutBody, NothingMovesAtTheInstantOfTheCut) {
  auto scene = uncutThread(60);  // taut, vibrating a little: velocities are not zero
  CurveBody& thread = threadOf(*scene);
  const double s_cut = 0.37;
  std::vector<Vec3> p, v;
  for (int k = 0; k <= 64; ++k) {
    p.push_back(thread.position(scene->state().q, k / 64.0));
    v.push_back(thread.position(scene->state().v, k / 64.0));  // Ṗ(s) = Σ b_j(s) v_j
  }
  const Vec3 p_cut = thread.position(scene->state().q, s_cut);
  const Energy e0 = scene->energy(scene->state());
  const int n = thread.pointCount();
  scene->cut(thread, s_cut);

  // s = 0.37 is no knot of the 27 uniform segments: 4 insertions.
  EXPECT_EQ(thread.pointCount(), n + 4);
  EXPECT_EQ(scene->layoutRevision(), 1);
  ASSERT_EQ(thread.basis().cuts().size(), 1u);
  EXPECT_NEAR(thread.basis().cuts()[0], s_cut, 1e-15);
  // Positions are sums of d + 1 = 4 products, exact to 4ε|q| ≈ 1e-17 m for |q| ~ 0.1 m (bound
  // 1e-15 m); velocities likewise to 4ε|v| (bound 1e-14 |v| + 1e-15 m/s).
  for (int k = 0; k <= 64; ++k) {
    EXPECT_LE((thread.position(scene->state().q, k / 64.0) - p[k]).norm(), 1e-15) << "s = " << k / 64.0;
    EXPECT_LE((thread.position(scene->state().v, k / 64.0) - v[k]).norm(), 1e-15 + 1e-14 * v[k].norm());
  }
  // Both ends at the cut are the old P(s): the right one through evaluate, the left one through
  // evaluateFromLeft (the end of the first strand).
  BasisRow left;
  thread.basis().evaluateFromLeft(thread.basis().cuts()[0], left);
  Vec3 p_left = Vec3::Zero();
  for (int j = 0; j < left.count; ++j) p_left += left.value[j] * thread.block(scene->state().q).row(left.first + j).transpose();
  EXPECT_LE((p_left - p_cut).norm(), 1e-15);
  EXPECT_LE((thread.position(scene->state().q, s_cut) - p_cut).norm(), 1e-15);
  // Energies: sums of at most ~10⁴ terms of a few ε each, 5e-12 of their magnitude; the bending
  // energy cancels (refine_body_test.cpp: ~3e-14 J here, EI = 1.6e-7 N m², h = 3.7 mm), 1e-12 J on top.
  const Energy e1 = scene->energy(scene->state());
  const double scale = std::abs(e0.kinetic) + std::abs(e0.potential);
  EXPECT_LE(std::abs(e1.kinetic - e0.kinetic), 5e-12 * scale);
  EXPECT_LE(std::abs(e1.potential - e0.potential), 5e-12 * scale + 1e-12);
}

/// After `scene` is cut at s: no mass, force or stiffness entry joins the two strands.
void expectStrandsUncoupled(Scene& scene, double s_cut) {
  CurveBody& thread = threadOf(scene);
  scene.cut(thread, s_cut);
  const int a = secondStrandStart(thread), n = thread.pointCount();
  ASSERT_GT(a, 0);
  ASSERT_LT(a, n);

  // Mass: M_ij = m ∫ b_i b_j ds is zero when no span holds both functions (exactly: no term).
  Triplets mass;
  TripletAccumulator mass_accumulator(mass);
  scene.bodies()[0]->addMassMatrix(1.0, mass_accumulator);
  ASSERT_FALSE(mass.empty());
  for (const auto& e : mass)
    if ((e.row() < 3 * a) != (e.col() < 3 * a)) {
      EXPECT_EQ(e.value(), 0.0) << "M(" << e.row() << ", " << e.col() << ")";
    }

  // Forces on strand 1 do not depend on strand 2: moving strand 2's points anywhere (and their
  // velocities) leaves them bit for bit the same (each span's integrand holds its own d + 1
  // points only, the spans of zero length at the cut hold no quadrature point, and no spring
  // joins samples of two strands).
  SceneState s = scene.state();
  VecX f0(scene.velocitySize());
  scene.computeForce(s, f0);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-0.01, 0.01);
  for (int i = 3 * a; i < 3 * n; ++i) {
    s.q[i] += uniform(random);
    s.v[i] += 100 * uniform(random);
  }
  VecX f1(scene.velocitySize());
  scene.computeForce(s, f1);
  for (int i = 0; i < 3 * a; ++i) EXPECT_EQ(f0[i], f1[i]) << "coordinate " << i;

  // Stiffness and damping: no entry of K or D couples the strands.
  Triplets entries;
  TripletAccumulator accumulator(entries);
  scene.addForceJacobian(scene.state(), 1.0, 1.0, accumulator);
  ASSERT_FALSE(entries.empty());
  for (const auto& e : entries)
    if ((e.row() < 3 * a) != (e.col() < 3 * a)) {
      EXPECT_EQ(e.value(), 0.0) << "(" << e.row() << ", " << e.col() << ")";
    }
}

TEST(CutBody, NoMassForceOrStiffnessJoinsTheTwoStrands) {
  // Real material: Green–Lagrange stretching, curvature bending, Rayleigh and viscous damping.
  auto scene = uncutThread(60);
  expectStrandsUncoupled(*scene, 0.5);
}

TEST(CutBody, NoSpringOfThePapersEnergyJoinsTheTwoStrands) {
  // The paper's springs between samples of the curve (SpringForceField), with a dashpot.
  test::CollisionThread thread;
  thread.control_points = {{"from", {0, 0, 0}}, {"to", {0.1, 0, 0}}, {"count", 20}};
  thread.constraints = nlohmann::json::array({{{"type", "FixedPointConstraint"}, {"abscissa", 0.0}}});
  auto scene = test::loadCollisionScene(test::collisionScene({thread}, {{"type", "ContactPipeline"}}));
  for (int k = 0; k < 100; ++k) ASSERT_TRUE(scene->step().ok);
  expectStrandsUncoupled(*scene, 0.43);
}

TEST(CutBody, ABodyIsCutOnceAtAnAbscissaInsideIt) {
  auto scene = uncutThread(1);
  CurveBody& thread = threadOf(*scene);
  scene->cut(thread, 0.5);
  const int n = thread.pointCount();
  for (const double s : {0.5, 0.0, 1.0, -0.2, std::nan("")}) {
    try {
      scene->cut(thread, s);
      ADD_FAILURE() << "a cut at " << s << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("/nodes/0/components/0"), std::string::npos) << e.what();
    }
    EXPECT_EQ(thread.pointCount(), n) << "a refused cut changed the body";
    EXPECT_EQ(scene->layoutRevision(), 1);
  }
  // A second cut elsewhere is a third strand.
  scene->cut(thread, 0.25);
  EXPECT_EQ(strands(thread.basis()).size(), 3u);
}

TEST(CutBody, AScheduledCutOutsideTheCurveIsRefusedWithItsPlace) {
  nlohmann::json document = readJsonFile(kCutThread);
  document["nodes"][0]["components"][0]["cuts"] = {{{"time", 0.05}, {"abscissa", 1.5}}};
  try {
    loadScene(document, "bad cut", app::makeFactory());
    FAIL() << "a cut at 1.5 was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/nodes/0/components/0/cuts/0/abscissa"), std::string::npos) << e.what();
  }
  document["nodes"][0]["components"][0]["cuts"] = {{{"time", 0.05}, {"abscissa", 0.5}}, {{"time", 0.05}, {"abscissa", 0.6}}};
  try {
    loadScene(document, "bad cut", app::makeFactory());
    FAIL() << "two cuts at one time were accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/nodes/0/components/0/cuts/1/time"), std::string::npos) << e.what();
  }
}

TEST(CutBody, AScheduledCutThatFailsIsTheStepsReportedFault) {
  // The same abscissa twice: the second cut finds the body already cut there; its step reports
  // it (nothing is thrown out of Scene::step) and leaves the state as it was.
  nlohmann::json document = readJsonFile(kCutThread);
  document["nodes"][0]["components"][0]["cuts"] = {{{"time", 0.0}, {"abscissa", 0.5}}, {{"time", 0.002}, {"abscissa", 0.5}}};
  auto scene = loadScene(document, "cut twice", app::makeFactory());
  ASSERT_TRUE(scene->step().ok);
  ASSERT_TRUE(scene->step().ok);
  const SceneState before = scene->state();
  const StepReport report = scene->step();
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.message.find("scheduled cut failed"), std::string::npos) << report.message;
  EXPECT_NE(report.message.find("not cut yet"), std::string::npos) << report.message;
  EXPECT_EQ(scene->state().q, before.q);
  EXPECT_EQ(scene->state().v, before.v);
  EXPECT_EQ(scene->layoutRevision(), 1);
}

TEST(CutBody, AHeldThreadCutInTheMiddleFallsInTwoHalves) {
  auto scene = loadScene(kCutThread, app::makeFactory());
  CurveBody& thread = threadOf(*scene);
  const ContactPipeline& pipeline = test::pipelineOf(*scene);
  const auto& model = *pipeline.models().at(0);
  const double g = 9.81, L = 0.1, r = 1e-4, table = -0.04;
  const double rho_a = 910 * M_PI * r * r;  // kg/m
  // The lowest energy the halves could reach: each hanging straight down from its grasper, its
  // centre of mass L/4 below it, E_eq = −(ρA L) g L/4 (the table only keeps them higher), lowered
  // by the stretch under the weight, at most ρ A g (L/2) / (E A) = 2.3e-9 of it: 1e-6 slack.
  const double e_hanging = -(rho_a * L) * g * L / 4;
  double e_previous = 0.0;
  bool cut = false, landed = false;
  long steps_with_contacts = 0;
  for (long step = 0; step < 1500; ++step) {
    const StepReport report = scene->step();
    ASSERT_TRUE(report.ok) << "step " << step << ": " << report.message;
    const double e = scene->energy(scene->state()).total();
    landed = landed || !pipeline.contacts().empty();
    if (!cut && scene->layoutRevision() == 1) {
      cut = true;
      EXPECT_NEAR(scene->state().time, 0.1 + 1e-3, 1e-12);  // the step that starts at 0.1 s
      EXPECT_EQ(strands(thread.basis()).size(), 2u);
    } else if (cut) {
      // Until the halves touch the table nothing drives them (fixed graspers): backward Euler,
      // Rayleigh and viscous damping only take energy out. (Contacts then may give some back:
      // Baumgarte's term pushes a penetration out.) Slack: round-off of E, ~1e-16 |E|.
      if (!landed) {
        EXPECT_LE(e, e_previous + 1e-15 * std::abs(e_hanging)) << "t = " << scene->state().time;
      }
      EXPECT_GE(e, e_hanging * (1 + 1e-6)) << "t = " << scene->state().time;
    }
    e_previous = e;
    if (!cut) continue;

    // Collision: one chord fewer than the centres' gaps, missing exactly at the cut, and no
    // contact holds points of both strands.
    const auto& mapping = model.mapping();
    int gaps = 0;
    for (int k = 0; k + 1 < model.sphereCount(); ++k)
      if (!mapping.joinsNext(k)) {
        ++gaps;
        EXPECT_EQ(mapping.abscissas()[k], thread.basis().cuts()[0]);
        EXPECT_EQ(mapping.abscissas()[k + 1], thread.basis().cuts()[0]);
      }
    EXPECT_EQ(gaps, 1);
    const int a = secondStrandStart(thread);
    for (const Contact& c : pipeline.contacts()) {
      bool first = false, second = false;
      const PointWeights& w = c.a.weights();
      for (int j = 0; j < w.count; ++j) (w.point[j] < a ? first : second) |= w.weight[j] != 0.0;
      EXPECT_NE(first, second) << "a contact spans the cut at t = " << scene->state().time;
    }
    steps_with_contacts += !pipeline.contacts().empty();
  }
  ASSERT_TRUE(cut);
  EXPECT_GT(steps_with_contacts, 100) << "the halves were expected to rest on the table";
  // Held: both graspers' points stay put (a Lagrange row each at every step: the 3 × 3 solves'
  // round-off, with Baumgarte correcting any drift; 1e-9 m is a thousandth of a micrometre).
  EXPECT_LE(thread.position(scene->state().q, 0.0).norm(), 1e-9);
  EXPECT_LE((thread.position(scene->state().q, 1.0) - Vec3(L, 0, 0)).norm(), 1e-9);
  // Fallen in two halves: the cut ends rest on the table, one radius above it (the contact rows
  // are solved to ~1e-6 of the radius: apps/framed_chain_scene_test.cpp). Each half leans as a
  // strut from its grasper to the table, its foot √((L/2)² − (0.04 − r)²) from the grasper in x,
  // so the cut ends are L − 2 √((L/2)² − (0.04 − r)²) = 0.03973 m apart. The struts bend under
  // their weight by ~5 w L⁴/(384 EI) ≈ 1e-4 m (w = ρAg cos θ), which shortens each by
  // (8/3) δ²/(L/2) ≈ 1e-6 m, and stretch by 2e-9 of L: 1e-5 m covers both.
  BasisRow left;
  thread.basis().evaluateFromLeft(0.5, left);
  Vec3 free_left = Vec3::Zero();
  for (int j = 0; j < left.count; ++j) free_left += left.value[j] * thread.block(scene->state().q).row(left.first + j).transpose();
  const Vec3 free_right = thread.position(scene->state().q, 0.5);
  EXPECT_NEAR(free_left.z(), table + r, 1e-6 * r);
  EXPECT_NEAR(free_right.z(), table + r, 1e-6 * r);
  const double drop = -table - r;
  EXPECT_NEAR((free_right - free_left).norm(), L - 2 * std::sqrt(L * L / 4 - drop * drop), 1e-5);
}

}  // namespace
}  // namespace filum::collision
