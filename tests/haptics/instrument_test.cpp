// Instruments (haptics/instrument_set.hpp): a grasp holds below its holding force and slips
// above it, to where the spring–slider puts it; jaws holding a thread let the held piece through
// and push another thread that comes down on them; scissors cut at the abscissa between their blades
// at the step their gap closes onto the thread, and cut nothing in the air; a cut that needs
// coagulation is refused until bipolar forceps have coagulated the span; the trainee metrics of a
// scripted path against values worked out by hand; every instrument field refused at its JSON path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "filum/collision/register_components.hpp"
#include "filum/collision/segment_closest_points.hpp"
#include "filum/constraints/register_components.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/haptics/instrument_set.hpp"
#include "filum/mechanics/register_components.hpp"

namespace filum::haptics {
namespace {

using nlohmann::json;

// The test thread: 3-0 braided silk (radius 0.11 mm, 1300 kg/m³, E = 8.7 GPa; bending 5e8 Pa as
// in apps/scenes/knot.json), 10 cm along x from the origin, held at s = 0, no gravity; 40 control
// points: P(s) = (0.1 s, 0, 0) exactly (a uniform B-spline reproduces a line).
constexpr double kLength = 0.1, kRadius = 1.1e-4, kModulus = 8.7e9;
const double kAxialStiffness = kModulus * M_PI * kRadius * kRadius;  // E A (N)

json threadScene(const json& instruments, bool collision = true) {
  const json points = {{"from", {0, 0, 0}}, {"to", {kLength, 0, 0}}, {"count", 40}};
  json components = json::array({{{"type", "DynamicSpline"}, {"control_points", points}, {"radius", kRadius},
                                  {"density", 1300}},
                                 {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", kModulus}},
                                 {{"type", "CurvatureBending"}, {"youngs_modulus", 5e8}},
                                 {{"type", "ViscousDamping"}, {"coefficient", 1.0}},
                                 {{"type", "FixedPointConstraint"}, {"abscissa", 0.0}}});
  if (collision)
    components.push_back({{"type", "SphereCollisionModel"}, {"spacing", 2 * kRadius}, {"self_collision", false}});
  json scene{{"name", "instrument test"}, {"dt", 1e-3}, {"duration", 2.0}, {"gravity", {0, 0, 0}},
             {"integrator", {{"type", "ImplicitEuler"}}},
             {"nodes", json::array({{{"name", "thread"}, {"components", components}}})},
             {"instruments", instruments}};
  if (collision) scene["collision"] = {{"type", "ContactPipeline"}, {"response", "unilateral"}};
  return scene;
}

struct InstrumentRun {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<InstrumentSet> instruments;
  explicit InstrumentRun(const json& document) {
    Factory factory;
    mechanics::register_components(factory);
    constraints::register_components(factory);
    collision::register_components(factory);
    scene = loadScene(document, "instrument test", factory);
    instruments = InstrumentSet::fromScene(document, "instrument test", *scene);
  }
  /// One step with the instruments' work around it; false when the step failed.
  bool step() {
    instruments->beforeStep(*scene);
    const StepReport report = scene->step();
    if (report.ok) instruments->afterStep(*scene);
    return report.ok;
  }
  const CurveBody& thread() const { return *scene->bodies().front()->curve(); }
  int strands() const { return static_cast<int>(strandsOf(thread().basis()).size()); }
  static std::vector<Strand> strandsOf(const CurveBasis& basis) { return filum::strands(basis); }
};

/// A grasper from −y (shaft along +y), jaws opening up and down (roll 0): caught at x = 0.05
/// (s = 0.5) as the jaws close over 0–0.1 s, then the jaws are carried `pull` metres along +x over
/// 0.1–1.1 s and held there.
json pullingGrasper(double holding_force, double pull) {
  return json::array({{{"name", "grasper"}, {"type", "Grasper"}, {"holding_force", holding_force},
                       {"path", json::array({{{"time", 0.0}, {"position", {0.05, -0.01, 0}}, {"direction", {0, 1, 0}},
                                              {"jaw", 1}},
                                             {{"time", 0.1}, {"position", {0.05, -0.01, 0}}, {"jaw", 0}},
                                             {{"time", 1.1}, {"position", {0.05 + pull, -0.01, 0}}}})}}});
}

TEST(Grasp, JawsCatchEachPartOfARodAtThatPartsRadius) {
  // A straight rod along x whose second half is a thin tip ("spans": 0.4 mm against the shaft's
  // 1 mm). Jaws across it (shaft along +y, opening along z), the rod 10 mm from the hinge, close
  // from wide open to a gap of 2 × 0.7 mm there (jawsClosedOn: along · sin φ − r_jaw = 0.7 mm):
  // onto the shaft's 1 mm, not onto the tip's 0.4 mm, which one radius for the rod would catch;
  // closed to 2 × 0.3 mm they catch the tip.
  Factory factory;
  mechanics::register_components(factory);
  const json rod = {{"type", "FramedChain"}, {"nodes", {{"from", {0, 0, 0}}, {"to", {0.2, 0, 0}}, {"count", 21}}},
                    {"radius", 1e-3}, {"density", 1150},
                    {"spans", {{{"from", 0.5}, {"to", 1.0}, {"radius", 4e-4}}}}};
  const json document{{"name", "jaws on a rod"}, {"dt", 1e-3}, {"gravity", {0, 0, 0}},
                      {"nodes", json::array({{{"name", "rod"}, {"components", json::array({rod})}}})}};
  auto scene = loadScene(document, "jaws on a rod", factory);
  scene->init();
  const InstrumentShape shape;  // jaw radius 1 mm, length 18 mm, 0.9 rad fully open
  const double along = 0.01;
  auto openingFor = [&](double half_gap) {  // o with along · sin(o · max/2) − r_jaw = half_gap
    return 2.0 * std::asin((half_gap + shape.jaw_radius) / along) / shape.max_angle;
  };
  auto caughtAt = [&](double x, double half_gap) {
    InstrumentPose pose;
    pose.hinge = Vec3(x, -along, 0);
    pose.frame = instrumentFrame(Vec3::UnitY(), 0.0);
    return catchBetweenJaws(*scene, shape, pose, 1.0, openingFor(half_gap));
  };
  const auto shaft = caughtAt(0.05, 0.7e-3);
  ASSERT_TRUE(shaft.has_value());
  // The nearest point to the jaws' midline is the rod's point under the hinge, s = 0.25, to the
  // golden-section search's 0.618⁴⁰ ≈ 4.4e-9 of its bracket of two samples (at most 2/63 in s).
  EXPECT_NEAR(shaft->abscissa, 0.25, 1e-9);
  EXPECT_FALSE(caughtAt(0.15, 0.7e-3).has_value());
  const auto tip = caughtAt(0.15, 0.3e-3);
  ASSERT_TRUE(tip.has_value());
  EXPECT_NEAR(tip->abscissa, 0.75, 1e-9);
}

TEST(Grasp, HoldsBelowItsHoldingForce) {
  // A 0.5 mm pull stretches the coupling (k = 500 N/m) in series with the held 5 cm of thread
  // (EA/0.05 = 6.6e3 N/m): 0.23 N, far below a 5 N hold. The held abscissa never moves.
  InstrumentRun run(threadScene(pullingGrasper(5.0, 5e-4)));
  double caught = -1.0, largest = 0.0;
  for (int k = 0; k < 1300; ++k) {
    ASSERT_TRUE(run.step()) << "step " << k;
    const Instrument& grasper = run.instruments->instrument(0);
    if (grasper.holding() && caught < 0.0) caught = grasper.hold()->grasp.abscissa();
    if (grasper.holding()) {
      EXPECT_EQ(grasper.hold()->grasp.abscissa(), caught) << "t = " << run.scene->state().time;
      largest = std::max(largest, run.instruments->holdForce(0, *run.scene).norm());
    }
  }
  // Caught where the thread crosses the jaws' midline: P(s) = (0.1 s, 0, 0) meets x = 0.05 at
  // s = 0.5; the golden-section search stops within 1e-8 of the bracket (40 steps).
  EXPECT_NEAR(caught, 0.5, 1e-6);
  // At rest the coupling bears the whole stretch: k_series Δx with 1/k_series = 1/k + 0.05/EA.
  const double k_series = 1.0 / (1.0 / 500.0 + 0.05 / kAxialStiffness);
  const double at_rest = run.instruments->holdForce(0, *run.scene).norm();
  // The thread's viscous damping (1/s) has let the pull settle for 0.2 s past the end of the
  // motion: the remaining transient is below 1e-3 of the force (the thread's axial modes, at
  // kHz, are gone; the coupling's own relaxation time c/k is 0.1 ms).
  EXPECT_NEAR(at_rest, k_series * 5e-4, 1e-3 * k_series * 5e-4);
  EXPECT_LT(largest, 5.0);
  EXPECT_EQ(run.instruments->metrics().instrument(0).grasps, 1);
  EXPECT_EQ(run.instruments->metrics().instrument(0).slip_length, 0.0);
}

TEST(Grasp, AThreadPulledThroughTheJawsLeavesThemAtACutNotOntoTheOtherStrand) {
  // The thread cut at s = 0.6 before the first step (a scheduled cut): the grasper catches s = 0.5
  // and draws 3 cm along +x against a 0.05 N hold. The strand [0, 0.6] slides through the jaws
  // until its cut end passes them: the grasp lets go there, and never holds s > 0.6.
  json document = threadScene(pullingGrasper(0.05, 0.03));
  document["nodes"][0]["components"][0]["cuts"] = json::array({{{"time", 0.0}, {"abscissa", 0.6}}});
  InstrumentRun run(document);
  double largest = 0.0;
  bool held = false;
  for (int k = 0; k < 1300; ++k) {
    ASSERT_TRUE(run.step()) << "step " << k;
    const Instrument& g = run.instruments->instrument(0);
    if (g.holding()) {
      held = true;
      largest = std::max(largest, g.hold()->grasp.abscissa());
    }
  }
  EXPECT_TRUE(held);
  EXPECT_FALSE(run.instruments->instrument(0).holding());
  EXPECT_LE(largest, 0.6);
  bool pulled_out = false;
  for (const std::string& e : run.instruments->events()) pulled_out = pulled_out || e.find("pulled out") != std::string::npos;
  EXPECT_TRUE(pulled_out);
}

TEST(Grasp, SlipsAboveItsHoldingForceToWhereTheSliderStops) {
  // A 2 cm pull against a 0.5 N hold: once the coupling's pull along the thread reaches 0.5 N the
  // thread slides through the jaws. At rest the jaws bear exactly F_hold (the last slip left the
  // coupling stretched by F_hold/k along the thread) and the held 5–7 cm of thread carries F_hold:
  //   X_end − P(s_end) = F_hold/k,  P(s) = s L (1 + F_hold/EA)  ⇒  s_end = (X_end − F_hold/k) / (L (1 + F_hold/EA)).
  constexpr double hold = 0.5, pull = 0.02, k = 500.0;
  InstrumentRun run(threadScene(pullingGrasper(hold, pull)));
  for (int step = 0; step < 1400; ++step) ASSERT_TRUE(run.step()) << "step " << step;
  const Instrument& grasper = run.instruments->instrument(0);
  ASSERT_TRUE(grasper.holding());
  const double predicted = (0.05 + pull - hold / k) / (kLength * (1.0 + hold / kAxialStiffness));
  // The slider stops within one step of the jaws' travel of its rest (the force at rest lies in
  // [F_hold − k v h, F_hold] for the last jaw speed v; the path ends at rest, v → 0), i.e. well
  // within one jaw step at the path's top speed, 1.5 pull/T · h = 3e-5 m: 3e-4 in s.
  EXPECT_NEAR(grasper.hold()->grasp.abscissa(), predicted, 1.5 * pull / 1.0 * 1e-3 / kLength);
  // The tangential force never exceeds F_hold by more than one step of jaw travel at top speed.
  const Vec3 force = run.instruments->holdForce(0, *run.scene);
  EXPECT_LE(force.norm(), hold * (1.0 + 1e-3));
  // The length of thread that went through the jaws, on the thread stretched by F_hold/EA: from
  // the caught point, 0.05 (1 + ε), to the held one, X_end − F_hold/k.
  const double strain = hold / kAxialStiffness;
  EXPECT_NEAR(run.instruments->metrics().instrument(0).slip_length, 0.05 + pull - hold / k - 0.05 * (1 + strain),
              2 * 1.5 * pull * 1e-3);
}

TEST(Grasp, TheJawsLetTheHeldPieceThroughAndPushEverythingElse) {
  // The grasper of pullingGrasper holds the test thread A at s = 0.5 (x = 0.05) and stays; its
  // closed jaws are one capsule of radius R = 1 mm along +y from the hinge (0.05, −0.01, 0), 18 mm
  // long, A crossing it 10 mm from the hinge. A second thread B, 4 cm along x at y = 4 mm (14 mm
  // along the jaws) and 3 mm above them, is drawn taut first (its ends 0.1 mm apart each over
  // 0–0.1 s: 0.5 % strain, 1.7 N, so that it moves as a string), then its ends are carried 4 mm
  // down over 0.2–0.7 s: it comes down onto the jaws and drapes over them. Before the jaws pushed
  // while holding (the hold was then the jaws' only contact), B went through them.
  constexpr double kJawRadius = 1e-3;
  json document = threadScene(pullingGrasper(5.0, 0.0));
  json b = document["nodes"][0];
  b["name"] = "other";
  b["components"][0]["control_points"] = {{"from", {0.03, 0.004, 0.003}}, {"to", {0.07, 0.004, 0.003}}, {"count", 20}};
  auto end = [](double s, double x0, double x1) {
    return json{{"type", "FixedPointConstraint"}, {"abscissa", s}, {"interpolation", "smooth"},
                {"path", json::array({{{"time", 0.0}, {"position", {x0, 0.004, 0.003}}},
                                      {{"time", 0.1}, {"position", {x1, 0.004, 0.003}}},
                                      {{"time", 0.2}, {"position", {x1, 0.004, 0.003}}},
                                      {{"time", 0.7}, {"position", {x1, 0.004, -0.001}}}})}};
  };
  b["components"][4] = end(0.0, 0.03, 0.0299);
  b["components"].push_back(end(1.0, 0.07, 0.0701));
  document["nodes"].push_back(b);
  InstrumentRun run(document);
  const Vec3 hinge(0.05, -0.01, 0.0), tip(0.05, 0.008, 0.0);
  auto distanceToJaws = [&](const Vec3& x) {
    const double u = collision::closestParameterOnSegment(hinge, tip, x);
    return (x - (hinge + u * (tip - hinge))).norm();
  };
  const CurveBody& other = *run.scene->bodies()[1]->curve();
  double nearest = 1.0;  // of B's centre line to the jaws' axis, over the run (m)
  for (int k = 0; k < 900; ++k) {
    ASSERT_TRUE(run.step()) << "step " << k;
    const auto q = other.block(run.scene->state().q);
    for (int i = 0; i <= 200; ++i) nearest = std::min(nearest, distanceToJaws(geometry::curvePoint(other.basis(), q, i / 200.0)));
  }
  const Instrument& grasper = run.instruments->instrument(0);
  ASSERT_TRUE(grasper.holding());
  // B rests on the jaws: its centre line R + r from their axis, less what the contact rows let it
  // sink in (Baumgarte's correction of a gap held near zero: a small fraction of r under a 1 N
  // press); half of r is a margin for that, and far above going through (distance 0).
  EXPECT_GT(nearest, kJawRadius + 0.5 * kRadius);
  EXPECT_LT(nearest, kJawRadius + 2.0 * kRadius);  // it did come down onto them
  // A's held point stays between the jaws, at their axis: the hold holds it, no contact pushes it.
  EXPECT_LT(distanceToJaws(grasper.hold()->grasp.map(run.scene->state().q)), 0.5 * kJawRadius);
  // The piece let through: the held point ± (jaw length + R + r) along A, 19.11 mm of its 10 cm
  // (0.1911 in s, A being nearly unstretched); farther along, A is pushed as B is.
  const double s = grasper.hold()->grasp.abscissa();
  for (int part = 1; part <= 2; ++part) {
    EXPECT_TRUE(grasper.part(part)->passesThrough(run.thread(), s + 0.19));
    EXPECT_TRUE(grasper.part(part)->passesThrough(run.thread(), s - 0.19));
    EXPECT_FALSE(grasper.part(part)->passesThrough(run.thread(), s + 0.195));
    EXPECT_FALSE(grasper.part(part)->passesThrough(other, s));
    EXPECT_TRUE(grasper.part(part)->enabled());
  }
}

/// Scissors from −y (blades opening up and down) at x = `x`, `height` above the thread, closing
/// from fully open to shut over 0.1–0.3 s.
json scissorsAt(double x, double height, bool require_coagulation = false) {
  json s = {{"name", "scissors"}, {"type", "Scissors"},
            {"path", json::array({{{"time", 0.0}, {"position", {x, -0.01, height}}, {"direction", {0, 1, 0}},
                                   {"jaw", 1}},
                                  {{"time", 0.1}, {"position", {x, -0.01, height}}, {"jaw", 1}},
                                  {{"time", 0.3}, {"position", {x, -0.01, height}}, {"jaw", 0}}})}};
  if (require_coagulation) s["require_coagulation"] = true;
  return s;
}

TEST(Scissors, CutBetweenTheBladesAtTheStepTheyCloseOntoTheThread) {
  InstrumentRun run(threadScene(json::array({scissorsAt(0.03, 0.0)})));
  // The gap between the blades' surfaces at the thread (10 mm from the hinge) falls to its
  // diameter when 0.01 sin φ − r_jaw = r, φ = o · 0.45 rad: o* = asin((r_jaw + r)/0.01)/0.45; the
  // opening follows o(t) = 1 − σ((t − 0.1)/0.2), σ(u) = 3u² − 2u³ (instrument_path.hpp), so the
  // cut comes at the first step whose start time t_k = k h has o(t_k) <= o*.
  const double o_star = std::asin((1e-3 + kRadius) / 0.01) / 0.45;
  double lo = 0.0, hi = 1.0;  // σ(u) = 1 − o* by bisection (σ increases on [0, 1])
  for (int it = 0; it < 60; ++it) {
    const double u = 0.5 * (lo + hi);
    (u * u * (3 - 2 * u) < 1 - o_star ? lo : hi) = u;
  }
  const long expected_step = static_cast<long>(std::ceil((0.1 + 0.2 * hi) / 1e-3 - 1e-9));
  long cut_step = -1;
  for (int k = 0; k < 400 && cut_step < 0; ++k) {
    const long before = run.scene->stepCount();
    run.instruments->beforeStep(*run.scene);
    if (run.strands() == 2) cut_step = before;
    ASSERT_TRUE(run.scene->step().ok);
    run.instruments->afterStep(*run.scene);
  }
  EXPECT_EQ(cut_step, expected_step);
  const std::vector<Strand> strands = InstrumentRun::strandsOf(run.thread().basis());
  ASSERT_EQ(strands.size(), 2u);
  // The blades' midline crosses the straight thread at x = 0.03: s = 0.3 (golden section: 1e-8).
  EXPECT_NEAR(strands[0].end, 0.3, 1e-6);
  EXPECT_EQ(run.instruments->metrics().instrument(0).cuts, 1);
}

TEST(Scissors, CutNothingWhenTheyCloseOnAir) {
  // The same scissors 5 mm above the thread: it is never between the blades (their plane's
  // thickness is r_jaw + r = 1.1 mm about the hinge's height).
  InstrumentRun run(threadScene(json::array({scissorsAt(0.03, 0.005)})));
  for (int k = 0; k < 400; ++k) ASSERT_TRUE(run.step());
  EXPECT_EQ(run.strands(), 1);
  EXPECT_EQ(run.instruments->metrics().instrument(0).cuts, 0);
  ASSERT_FALSE(run.instruments->events().empty());
  EXPECT_NE(run.instruments->events().back().find("closed on nothing"), std::string::npos);
}

TEST(Scissors, RefuseAnUncoagulatedCutAndCutAfterBipolarForceps) {
  // Scissors that need coagulation close on the thread at x = 0.03 first (refused), then, after
  // bipolar forceps held x = 0.07 for their 0.2 s of coagulation, at x = 0.07 (cut, coagulated).
  json scissors = scissorsAt(0.03, 0.0, true);
  scissors["path"].push_back({{"time", 0.4}, {"position", {0.03, -0.01, 0}}, {"jaw", 1}});
  scissors["path"].push_back({{"time", 0.6}, {"position", {0.072, -0.01, 0}}, {"jaw", 1}});
  scissors["path"].push_back({{"time", 0.9}, {"position", {0.072, -0.01, 0}}, {"jaw", 1}});
  scissors["path"].push_back({{"time", 1.1}, {"position", {0.072, -0.01, 0}}, {"jaw", 0}});
  const json bipolar = {
      {"name", "bipolar"}, {"type", "BipolarForceps"}, {"coagulation_time", 0.2},
      {"path", json::array({{{"time", 0.0}, {"position", {0.07, 0.01, 0}}, {"direction", {0, -1, 0}}, {"jaw", 1}},
                            {{"time", 0.2}, {"position", {0.07, 0.01, 0}}, {"jaw", 0}},
                            {{"time", 0.6}, {"position", {0.07, 0.01, 0}}, {"jaw", 0}},
                            {{"time", 0.7}, {"position", {0.07, 0.01, 0}}, {"jaw", 1}},
                            {{"time", 0.8}, {"position", {0.07, 0.05, 0}}, {"jaw", 1}}})}};
  InstrumentRun run(threadScene(json::array({scissors, bipolar})));
  for (int k = 0; k < 1300; ++k) ASSERT_TRUE(run.step()) << "step " << k;
  const InstrumentTally& m = run.instruments->metrics().instrument(0);
  EXPECT_EQ(m.cuts_refused, 1);
  EXPECT_EQ(m.cuts, 1);
  EXPECT_EQ(m.cuts_coagulated, 1);
  EXPECT_EQ(run.instruments->metrics().instrument(1).coagulations, 1);
  // Coagulated: x = 0.07 ± half a jaw (9 mm) on the straight thread, s = 0.7 ± 0.09.
  EXPECT_TRUE(run.instruments->coagulated(run.thread(), 0.72));
  EXPECT_FALSE(run.instruments->coagulated(run.thread(), 0.5));
  const std::vector<Strand> strands = InstrumentRun::strandsOf(run.thread().basis());
  ASSERT_EQ(strands.size(), 2u);
  EXPECT_NEAR(strands[0].end, 0.72, 2e-3);  // the thread moved little: held at 0.7 for a while
}

TEST(TraineeMetrics, PathLengthIdleTimeAndTaskTimeOfAScriptedPath) {
  // A grasper far from the thread (no collision) rests at A for 0.2 s, moves 5 cm to B in 0.5 s,
  // rests 0.5 s, comes back in 0.5 s and rests to 2 s. Each move is the Hermite cubic with zero
  // end velocities (Fritsch–Butland velocities vanish at a pause), x = A + (B − A) σ(u): the tip
  // runs the straight segment twice, path length 2 |AB| = 0.1 m (to round-off), and moves slower
  // than v_idle = 5 mm/s while 6u(1−u) |AB|/T < v_idle: u(1−u) < v_idle T/(6|AB|), at each end
  // of each move.
  const json grasper = {
      {"name", "g"}, {"type", "Grasper"}, {"collide", false},
      {"path", json::array({{{"time", 0.0}, {"position", {0.05, -0.05, 0.05}}, {"direction", {0, 1, 0}}, {"jaw", 1}},
                            {{"time", 0.2}, {"position", {0.05, -0.05, 0.05}}},
                            {{"time", 0.7}, {"position", {0.10, -0.05, 0.05}}},
                            {{"time", 1.2}, {"position", {0.10, -0.05, 0.05}}},
                            {{"time", 1.7}, {"position", {0.05, -0.05, 0.05}}}})}};
  InstrumentRun run(threadScene(json::array({grasper}), false));
  for (int k = 0; k < 2000; ++k) ASSERT_TRUE(run.step());
  const InstrumentTally& m = run.instruments->metrics().instrument(0);
  EXPECT_NEAR(m.path_length, 0.1, 1e-12);
  EXPECT_NEAR(m.economy(), 0.0, 1e-12);  // back where it started
  const double v_idle = 5e-3, T = 0.5, d = 0.05;
  const double c = v_idle * T / (6 * d);
  const double u_slow = 0.5 * (1 - std::sqrt(1 - 4 * c));  // u(1−u) = c
  const double slow = 4 * u_slow * T;  // two ends of two moves
  // Rests: [0, 0.2] (0.2 s), [0.7, 1.2] (0.5 s), [1.7, 2.0] (0.3 s). A step is idle when its
  // displacement is below v_idle h: each of the 4 boundaries of a slow interval is found to
  // within one step (h = 1 ms).
  EXPECT_NEAR(m.idle_time, 1.0 + slow, 4e-3 + 1e-9);
  // Task time: from the first to the last step that moved faster than v_idle.
  const double first = 0.2 + u_slow * T, last = 1.7 - u_slow * T;
  EXPECT_NEAR(run.instruments->metrics().taskTime(), last - first, 2e-3 + 1e-9);
}

TEST(Trocar, TheShaftPassesThroughItsPortAtEveryStep) {
  // A grasper through a port 5 cm above and 5 cm before the thread, its hinge swept over a 3 cm
  // square above the thread: the shaft's axis (the segment from hinge − L d to the hinge) holds
  // the port at every step, to round-off (the frame is turned onto the port's direction exactly).
  const Vec3 port(0.05, -0.05, 0.05);
  const json grasper = {
      {"name", "g"}, {"type", "Grasper"}, {"trocar", {port.x(), port.y(), port.z()}}, {"shaft_length", 0.12},
      {"path", json::array({{{"time", 0.0}, {"position", {0.035, -0.01, 0.01}}, {"jaw", 1}},
                            {{"time", 0.3}, {"position", {0.065, -0.01, 0.01}}},
                            {{"time", 0.6}, {"position", {0.065, 0.02, 0.01}}, {"roll", 0.5}},
                            {{"time", 0.9}, {"position", {0.035, 0.02, 0.02}}}})}};
  InstrumentRun run(threadScene(json::array({grasper})));
  const Instrument& g = run.instruments->instrument(0);
  double worst = 0.0;
  for (int k = 0; k < 1000; ++k) {
    ASSERT_TRUE(run.step());
    const Capsule shaft = g.partNow(0);
    const Vec3 axis = (shaft.b - shaft.a).normalized();
    const Vec3 off = (port - shaft.a) - (port - shaft.a).dot(axis) * axis;  // the port's offset from the axis
    const double along = (port - shaft.a).dot(axis);
    EXPECT_GE(along, 0.0);
    EXPECT_LE(along, 0.12);
    worst = std::max(worst, off.norm());
  }
  // Round-off of a rotation of 0.1 m: a few ulps of 0.1 m.
  EXPECT_LT(worst, 1e-15 * 0.1 * 64);
}

/// A grasper on a scripted device (device frame = scene frame): from y = side · 6 cm to 1 cm of the
/// hanging thread at height z, button held from 0.3 s (the jaws close at 5/s), then drawn `pull`
/// along x over 0.5–1.0 s; `peak` its device's peak force (N).
json deviceGrasper(const std::string& name, double side, double z, double pull, double peak) {
  const json waypoints = json::array({{{"time", 0.0}, {"position", {0, side * 0.06, z}}},
                                      {{"time", 0.2}, {"position", {0, side * 0.01, z}}},
                                      {{"time", 0.3}, {"position", {0, side * 0.01, z}}, {"buttons", 1}},
                                      {{"time", 0.5}, {"position", {0, side * 0.01, z}}, {"buttons", 1}},
                                      {{"time", 1.0}, {"position", {pull, side * 0.01, z}}, {"buttons", 1}}});
  return {{"name", name}, {"type", "Grasper"}, {"holding_force", 1.5},
          {"device", {{"device", {{"type", "ScriptedDevice"}, {"model", "Touch"}, {"waypoints", waypoints}}},
                      {"limits", {{"peak_force", peak}, {"continuous_force", std::min(0.88, 0.8 * peak)}}},
                      {"direction", {0, -side, 0}}, {"roll", 1.5708}}}};
}

/// The test thread hanging from its top end (the x-aligned scene turned to hang along −z).
json hangingThreadScene(const json& instruments) {
  json scene = threadScene(instruments);
  scene["gravity"] = {0, 0, -9.81};
  scene["nodes"][0]["components"][0]["control_points"] = {{"from", {0, 0, 0}}, {"to", {0, 0, -kLength}}, {"count", 40}};
  return scene;
}

TEST(InstrumentDevices, TwoDevicesEachFeelTheirOwnForceWithinTheirOwnLimits) {
  // Two hands grasp the hanging thread at 3 and 7 cm and draw apart along x, 15 mm each: the 4 cm
  // between their grasps is stretched until it slips at the 1.5 N hold. Each hand feels the
  // thread pull it back (left, drawn to −x, is pulled to +x; right the opposite), through its own
  // coupling, clamped by its own device: the left's peak force is 0.3 N, the right's 3.3 N (a Touch).
  InstrumentRun run(hangingThreadScene(json::array({deviceGrasper("left", -1.0, -0.03, -0.015, 0.3),
                                                    deviceGrasper("right", 1.0, -0.07, 0.015, 3.3)})));
  for (int k = 0; k < 1200; ++k) ASSERT_TRUE(run.step()) << "step " << k;
  const InstrumentSet& set = *run.instruments;
  ASSERT_TRUE(set.instrument(0).holding());
  ASSERT_TRUE(set.instrument(1).holding());
  double left_peak = 0.0, right_peak = 0.0, left_commanded = 0.0, left_x = 0.0, right_x = 0.0;
  for (const ServoSample& s : set.device(0)->servo().log()) {
    left_peak = std::max(left_peak, s.sent.norm());
    left_commanded = std::max(left_commanded, s.commanded.norm());
    if (s.time > 0.6) left_x += s.sent.x();
  }
  for (const ServoSample& s : set.device(1)->servo().log()) {
    right_peak = std::max(right_peak, s.sent.norm());
    if (s.time > 0.6) right_x += s.sent.x();
  }
  // ForceSafety clamps |F| to the peak force exactly (a scaling of the vector).
  EXPECT_LE(left_peak, 0.3 * (1 + 1e-12));
  EXPECT_GT(left_commanded, 0.3);   // the left's own limit did the clamping
  EXPECT_GT(right_peak, 0.3);       // the right is not held to the left's limit
  EXPECT_LE(right_peak, 3.3 * (1 + 1e-12));
  EXPECT_GT(left_x, 0.0);  // each hand pulled back towards the other
  EXPECT_LT(right_x, 0.0);
}

TEST(NeedleHolder, CarriesTheNeedleRigidlyLetsGoAndAnotherTakesItOver) {
  // A 3/8-circle needle of radius 8 mm swaged to the thread's free end (s = 1, at x = 0.1), lying
  // in the horizontal plane, leaving the swage along the thread (+x: its centre at (0.1, R, 0), the
  // swage in direction u = −y from it, so v = ẑ × u = +x). Holder A closes on its wire from above
  // (0–0.1 s), carries it 2 cm along +y and 1 cm along −x (0.1–0.5 s), lets go (0.5–0.6 s) and
  // withdraws; holder B closes on it where it was left (0.7–0.8 s) and carries it 1 cm further
  // along −x (0.8–1.2 s).
  const double R = 0.008, arc = 2.356;
  const Vec3 centre(kLength, R, 0);
  const double mid = arc / 2;  // the wire's middle, where the jaws close
  // P(θ) = c + R (cos θ u + sin θ v) = c + R (sin θ, −cos θ, 0).
  const Vec3 wire = centre + R * Vec3(std::sin(mid), -std::cos(mid), 0);
  // The jaws' plane (shaft down, opening along n) must cross the wire: this needle is the one with
  // u = +x turned by −90° about z, so the jaws' roll is that one's, −atan2(cos θ, sin θ), plus π/2.
  const double roll = -std::atan2(std::cos(mid), std::sin(mid)) + M_PI / 2;
  auto holder = [&](const std::string& name, const json& path) {
    return json{{"name", name}, {"type", "NeedleHolder"}, {"path", path}};
  };
  const Vec3 a0 = wire + Vec3(0, 0, 0.01), a1 = a0 + Vec3(-0.01, 0.02, 0);
  const json path_a = json::array(
      {{{"time", 0.0}, {"position", {a0.x(), a0.y(), a0.z()}}, {"direction", {0, 0, -1}}, {"roll", roll}, {"jaw", 1}},
       {{"time", 0.1}, {"position", {a0.x(), a0.y(), a0.z()}}, {"jaw", 0}},
       {{"time", 0.5}, {"position", {a1.x(), a1.y(), a1.z()}}},
       {{"time", 0.6}, {"position", {a1.x(), a1.y(), a1.z()}}, {"jaw", 1}},
       {{"time", 0.8}, {"position", {a1.x(), a1.y(), a1.z() + 0.04}}}});
  const Vec3 b0 = a1 + Vec3(0, 0, 0.05), b1 = a1, b2 = a1 + Vec3(-0.01, 0, 0);
  const json path_b = json::array(
      {{{"time", 0.0}, {"position", {b0.x(), b0.y(), b0.z()}}, {"direction", {0, 0, -1}}, {"roll", roll}, {"jaw", 1}},
       {{"time", 0.6}, {"position", {b0.x(), b0.y(), b0.z()}}},
       {{"time", 0.7}, {"position", {b1.x(), b1.y(), b1.z()}}},
       {{"time", 0.8}, {"position", {b1.x(), b1.y(), b1.z()}}, {"jaw", 0}},
       {{"time", 1.2}, {"position", {b2.x(), b2.y(), b2.z()}}}});
  json document = threadScene(json::array({holder("A", path_a), holder("B", path_b)}));
  document["needles"] = json::array({{{"name", "needle"}, {"radius", R}, {"arc", arc}, {"wire_radius", 2.5e-4},
                                      {"center", {centre.x(), centre.y(), centre.z()}}, {"normal", {0, 0, 1}},
                                      {"start", {0, -1, 0}}, {"thread", "thread"}, {"abscissa", 1.0}}});
  InstrumentRun run(document);
  const Needle& needle = run.instruments->needle(0);
  const Vec3 swage0 = needle.swage(needle.pose());
  double worst_follow = 0.0, worst_rigid = 0.0;
  Vec3 left_at = Vec3::Zero();
  for (int k = 0; k < 1400; ++k) {
    ASSERT_TRUE(run.step()) << "step " << k;
    const double t = run.scene->state().time;
    const Vec3 swage = needle.swage(needle.pose());
    // Held by A: the needle moves with A's hinge (a translation: A's frame is fixed), exactly.
    if (needle.holder == 0) worst_rigid = std::max(worst_rigid, ((swage - swage0) - (run.instruments->instrument(0).pose().hinge - a0)).norm());
    if (t > 0.62 && t < 0.69) {
      if (left_at.isZero()) left_at = swage;
      EXPECT_EQ(needle.holder, -1);
      EXPECT_EQ(swage, left_at);  // let go, it stays
    }
    // The thread's end follows the swage through its stiff hold.
    if (t > 0.2) worst_follow = std::max(worst_follow, (run.thread().position(run.scene->state().q, 1.0) - swage).norm());
  }
  // A pure translation composed with rigid placements: round-off of 0.1 m.
  EXPECT_LT(worst_rigid, 1e-15 * 0.1 * 64);
  EXPECT_EQ(needle.holder, 1);
  // B carried it 1 cm along −x from where A left it.
  EXPECT_NEAR((needle.swage(needle.pose()) - left_at - Vec3(-0.01, 0, 0)).norm(), 0.0, 1e-12);
  // The swage moves at most 0.1 m/s: the thread's end trails it by about one step of that motion
  // (v h = 1e-4 m); the forces on the slack thread stretch the 2000 N/m hold by far less.
  EXPECT_LT(worst_follow, 1e-4);
  EXPECT_EQ(run.instruments->metrics().instrument(0).grasps, 1);
  EXPECT_EQ(run.instruments->metrics().instrument(1).grasps, 1);
  EXPECT_EQ(run.instruments->metrics().instrument(1).regrasps, 1);
}

TEST(NeedleHolder, TheHandTurnsTheHeldNeedleAboutItsOwnCentre) {
  // The needle of the test above, caught by holder A from above (0–0.1 s); at 0.2 s the hand takes
  // A over and turns the needle by 90° over 0.2 s ([ ] in filum view). A turn about the needle's
  // centre c and normal w moves every point x of it to c + R(φ)(x − c): the centre stays, the swage
  // turns by φ; by the turn's end φ = 90°, to the round-off of composing rigid placements (1e-16
  // of 0.1 m, a few dozen operations).
  const double R = 0.008, arc = 2.356, mid = arc / 2;
  const Vec3 centre(kLength, R, 0);
  const Vec3 wire = centre + R * Vec3(std::sin(mid), -std::cos(mid), 0);
  const double roll = -std::atan2(std::cos(mid), std::sin(mid)) + M_PI / 2;
  const Vec3 a0 = wire + Vec3(0, 0, 0.01);
  const json path = json::array(
      {{{"time", 0.0}, {"position", {a0.x(), a0.y(), a0.z()}}, {"direction", {0, 0, -1}}, {"roll", roll}, {"jaw", 1}},
       {{"time", 0.1}, {"position", {a0.x(), a0.y(), a0.z()}}, {"jaw", 0}}});
  json document = threadScene(json::array({{{"name", "A"}, {"type", "NeedleHolder"}, {"path", path}}}));
  document["needles"] = json::array({{{"name", "needle"}, {"radius", R}, {"arc", arc}, {"wire_radius", 2.5e-4},
                                      {"center", {centre.x(), centre.y(), centre.z()}}, {"normal", {0, 0, 1}},
                                      {"start", {0, -1, 0}}, {"thread", "thread"}, {"abscissa", 1.0}}});
  InstrumentRun run(document);
  const Needle& needle = run.instruments->needle(0);
  for (int k = 0; k < 200; ++k) ASSERT_TRUE(run.step());
  ASSERT_EQ(needle.holder, 0);
  // A script cannot be turned by hand until the hand takes it over.
  EXPECT_FALSE(run.instruments->turnNeedle(0, M_PI / 2, run.scene->state().time));
  ASSERT_TRUE(run.instruments->takeOver(0, run.scene->state().time));
  const RigidPose before = needle.pose();
  ASSERT_TRUE(run.instruments->turnNeedle(0, M_PI / 2, run.scene->state().time, 0.2));
  for (int k = 0; k < 300; ++k) ASSERT_TRUE(run.step());
  const RigidPose after = needle.pose();
  const Vec3 w = before.rotation.col(2);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(M_PI / 2, w).toRotationMatrix();
  EXPECT_LT((after.position - before.position).norm(), 64 * 1e-16 * 0.1);
  EXPECT_LT((needle.swage(after) - (before.position + turn * (needle.swage(before) - before.position))).norm(),
            64 * 1e-16 * 0.1);
  // Positive angles drive the needle towards its tip: the swage moved to where the wire was, a
  // quarter turn along it.
  EXPECT_LT((needle.swage(after) - needle.point(before, M_PI / 2)).norm(), 64 * 1e-16 * 0.1);
  // The hand's next stroke starts from where the turn left the jaws: the mouse, still where it was
  // when the turn began, steers the hinge there again, and nothing jumps (the turn's swing of the
  // hinge about the needle's centre is kept as an offset from the hand).
  run.instruments->steer(0, a0, run.scene->state().time);
  for (int k = 0; k < 10; ++k) ASSERT_TRUE(run.step());
  EXPECT_LT((needle.pose().position - after.position).norm(), 64 * 1e-16 * 0.1);
  EXPECT_LT((needle.swage(needle.pose()) - needle.swage(after)).norm(), 64 * 1e-16 * 0.1);
}

TEST(Trocar, TheHandTakesOverAtTheHingeAndSteersItThroughThePort) {
  // A trocar grasper given to the hand: taking over leaves the hinge where the script had it, and
  // steering to a hinge puts it there (the hand at its mirror through the port), to round-off.
  const Vec3 port(0.05, -0.05, 0.05);
  const json grasper = {{"name", "g"}, {"type", "Grasper"}, {"trocar", {port.x(), port.y(), port.z()}},
                        {"path", json::array({{{"time", 0.0}, {"position", {0.05, -0.01, 0.01}}, {"jaw", 0.5}}})}};
  InstrumentRun run(threadScene(json::array({grasper})));
  for (int k = 0; k < 10; ++k) ASSERT_TRUE(run.step());
  const double t = run.scene->state().time;
  const Vec3 before = run.instruments->instrument(0).poseAt(t).hinge;
  ASSERT_TRUE(run.instruments->takeOver(0, t));
  EXPECT_LT((run.instruments->instrument(0).poseAt(t).hinge - before).norm(), 1e-15);
  EXPECT_EQ(run.instruments->instrument(0).jawAt(t + 0.1), 0.5);  // the jaws stay until a key moves them
  const Vec3 target(0.06, -0.005, 0.015);
  run.instruments->steer(0, target, t);
  EXPECT_LT((run.instruments->instrument(0).poseAt(t).hinge - target).norm(), 1e-15);
  run.instruments->moveJaws(0, true, t);
  EXPECT_NEAR(run.instruments->instrument(0).jawAt(t + 0.05), 0.25, 1e-12);  // closing at 5 per second
}

struct BadField {
  const char* what;
  json instrument;  // merged into a valid grasper
  const char* pointer;
};

TEST(Instruments, EveryFieldIsRefusedAtItsJsonPath) {
  const json valid = {{"name", "g"}, {"type", "Grasper"},
                      {"path", json::array({{{"time", 0.0}, {"position", {0.05, -0.01, 0}}, {"direction", {0, 1, 0}}}})}};
  const std::vector<BadField> cases = {
      {"unknown type", {{"type", "Stapler"}}, "/instruments/0/type"},
      {"empty path", {{"path", json::array()}}, "/instruments/0/path"},
      {"jaw above 1", {{"path", json::array({{{"time", 0.0}, {"position", {0, 0, 0}}, {"direction", {0, 1, 0}}, {"jaw", 1.5}}})}},
       "/instruments/0/path/0/jaw"},
      {"zero direction", {{"path", json::array({{{"time", 0.0}, {"position", {0, 0, 0}}, {"direction", {0, 0, 0}}}})}},
       "/instruments/0/path/0/direction"},
      {"no direction", {{"path", json::array({{{"time", 0.0}, {"position", {0, 0, 0}}}})}}, "/instruments/0/path/0/direction"},
      {"times not increasing",
       {{"path", json::array({{{"time", 0.5}, {"position", {0, 0, 0}}, {"direction", {0, 1, 0}}},
                              {{"time", 0.5}, {"position", {0, 0, 0}}}})}},
       "/instruments/0/path/1/time"},
      {"close_below outside (0, 1)", {{"close_below", 1.5}}, "/instruments/0/close_below"},
      {"negative holding force", {{"holding_force", -1.0}}, "/instruments/0/holding_force"},
      {"zero jaw length", {{"jaw_length", 0.0}}, "/instruments/0/jaw_length"},
      {"jaws wider than a straight angle", {{"max_angle", 4.0}}, "/instruments/0/max_angle"},
      {"coagulation time on a grasper", {{"coagulation_time", 1.0}}, "/instruments/0/coagulation_time"},
      {"holding force on scissors", {{"type", "Scissors"}, {"holding_force", 1.0}}, "/instruments/0/holding_force"},
      {"coagulation demanded by a grasper", {{"require_coagulation", true}}, "/instruments/0/require_coagulation"},
      {"coagulation of an unknown node", {{"type", "Scissors"}, {"require_coagulation", {"tube"}}},
       "/instruments/0/require_coagulation"},
      {"a misspelt field", {{"holding_forc", 1.0}}, "/instruments/0/holding_forc"},
      {"no name", {{"name", nullptr}}, "/instruments/0/name"},
      {"a direction through a trocar", {{"trocar", {0.05, -0.05, 0.05}}}, "/instruments/0/path/0/direction"},
      {"a trocar out of the shaft's reach",
       {{"trocar", {0.05, -0.5, 0.05}}, {"path", json::array({{{"time", 0.0}, {"position", {0.05, -0.01, 0}}}})}},
       "/instruments/0/trocar"},
  };
  for (const BadField& c : cases) {
    json instrument = valid;
    for (const auto& [key, value] : c.instrument.items()) {
      if (value.is_null()) {
        instrument.erase(key);
      } else {
        instrument[key] = value;
      }
    }
    try {
      InstrumentRun run(threadScene(json::array({instrument})));
      ADD_FAILURE() << c.what << ": accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(c.pointer), std::string::npos) << c.what << ": " << e.what();
    }
  }
  // Two instruments of one name; a colliding instrument in a scene without collision.
  try {
    InstrumentRun run(threadScene(json::array({valid, valid})));
    ADD_FAILURE() << "a repeated name: accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/instruments/1/name"), std::string::npos) << e.what();
  }
  try {
    InstrumentRun run(threadScene(json::array({valid}), false));
    ADD_FAILURE() << "collide without a collision pipeline: accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/instruments/0/collide"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace filum::haptics
