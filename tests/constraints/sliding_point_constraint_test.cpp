// The sliding point of [Lenoir talk 2008] (suturing): the thread passes through a hole P0 while the
// abscissa s(t) in the hole is a free unknown, (∂g/∂s)ᵀλ = 0.
#include <gtest/gtest.h>

#include <iostream>

#include "filum/constraints/lagrange_multiplier_solver.hpp"
#include "filum/constraints/sliding_point_constraint.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "support/constraint_scenes.hpp"

namespace filum {
namespace {

using nlohmann::json;
using test::ConstraintThread;

const constraints::SlidingPointConstraint& hole(const Scene& scene, int k = 0) {
  int seen = 0;
  for (const Constraint* c : scene.constraints())
    if (const auto* h = dynamic_cast<const constraints::SlidingPointConstraint*>(c))
      if (seen++ == k) return *h;
  throw std::logic_error("no sliding point");
}

/// A 10 cm thread through a hole at its initial point of abscissa `s0`, its end s = 1 pulled by
/// a smooth scripted grip by `pull` (m) along +x and 1 cm up between t = 0.2 s and 2.2 s.
/// Gravity is along −x, away from the grip: the tail weighs on the hole like a weight on a rope
/// over a pulley and keeps the thread under tension. (Under a vertical gravity a free tail and
/// a sagging span on either side of a frictionless hole are an unstable pair of pulley weights:
/// the span sags, draws thread, sags more — the thread runs out unless friction holds it, as in
/// apps/scenes/sliding.json. That is physics, not a test of the constraint.)
json pulledThroughHole(double s0, double pull, double friction, int control_points = 10) {
  ConstraintThread t;
  t.control_points = control_points;
  t.constraints = {json{{"type", "SlidingPointConstraint"}, {"name", "hole"}, {"abscissa", s0}, {"friction", friction}},
                   json{{"type", "FixedPointConstraint"},
                        {"name", "grip"},
                        {"abscissa", 1.0},
                        {"interpolation", "smooth"},
                        {"path",
                         {{{"time", 0.2}, {"position", {0.1, 0.0, 0.0}}},
                          {{"time", 2.2}, {"position", {0.1 + pull, 0.0, 0.01}}}}}}};
  return test::constraintScene({t}, 1e-4, "RungeKutta4", {-3.0, 0.0, 0.0});
}

/// Sum of the chord lengths between the spring samples: the length the spring energy sees
/// (SpringForceField samples 2n points evenly in s).
double chordLength(const CurveBody& spline, const SceneState& s) {
  const int samples = 2 * spline.pointCount();
  const Points x = geometry::sampleCurve(spline.basis(), spline.block(s.q), samples);
  double length = 0.0;
  for (int k = 0; k + 1 < samples; ++k) length += (x.row(k + 1) - x.row(k)).norm();
  return length;
}

TEST(SlidingPoint, ThreadPassesThroughTheHoleWithin1e8WhileItSlides) {
  // The gap P(s) − P0 is held in all three directions: across the thread by the multipliers,
  // along it by the direct relation for s̈; both with the Baumgarte terms, and RK4 advances
  // (q, s) together: what is left is RK4's local error, O(dt⁵) — measured ~1e-11 m.
  auto scene = test::loadConstraintScene(pulledThroughHole(0.5, 0.025, 1e-4));
  const auto& h = hole(*scene);
  const Vec3 P0 = h.target().positionAt(0.0);
  double worst = 0.0, s_min = 1.0, s_max = 0.0;
  for (int k = 0; k < 30000; ++k) {
    ASSERT_TRUE(scene->step().ok);
    worst = std::max(worst, h.gap(scene->state()).norm());
    const double s = h.abscissa(scene->state());
    s_min = std::min(s_min, s);
    s_max = std::max(s_max, s);
  }
  std::cout << "  |P(s) - P0| <= " << worst << " m while s went from 0.5 to " << h.abscissa(scene->state())
            << " (range " << s_min << " .. " << s_max << ")\n";
  EXPECT_LE(worst, 1e-8);
  // Pulling the end 2.5 cm away draws about 2.5 cm of a 10 cm thread through: Δs ≈ −0.25
  // (less what the springs stretch and the tail's swing).
  EXPECT_LT(h.abscissa(scene->state()), 0.5 - 0.15);
  EXPECT_TRUE(h.active());
  // And the point in the hole is P0 (not merely some point on a line through it).
  EXPECT_LE((h.gap(scene->state())).norm(), 1e-8);
  EXPECT_EQ(h.target().positionAt(3.0), P0);
}

TEST(SlidingPoint, LengthIsConservedAsTheSpringsAllow) {
  // The hole neither creates nor removes thread: the length changes only by the springs'
  // elongation under tension. The spring energy measures the length as the chord sum of its
  // 2n samples; n = 10 gives 2n − 1 = 19 stretch springs of stiffness k in series, so with a
  // tension at most T along the thread the elongation is at most (2n − 1) T / k. T is bounded by
  // the grip's force |λ_grip| (the multipliers, N) plus the thread's weight m g; inertia and
  // the spring dashpots add transients, hence a factor 2 margin.
  const int n = 10;
  const double k = 1.0, weight = 2.86e-6 * 3.0;  // N (gravity 3 m/s² along −x)
  auto scene = test::loadConstraintScene(pulledThroughHole(0.5, 0.025, 1e-4, n));
  const auto& spline = *scene->bodies().front()->curve();
  const auto& solver = dynamic_cast<const constraints::LagrangeMultiplierSolver&>(*scene->constraintSolver());
  const double l0 = chordLength(spline, scene->state());
  double worst = 0.0, tension = 0.0, arc_worst = 0.0;
  for (int step = 0; step < 30000; ++step) {
    ASSERT_TRUE(scene->step().ok);
    tension = std::max(tension, solver.multipliers().tail<3>().norm());  // the grip's rows come last
    worst = std::max(worst, std::abs(chordLength(spline, scene->state()) - l0));
    arc_worst = std::max(arc_worst, std::abs(mechanics::arcLength(spline.basis(), spline.block(scene->state().q)) - 0.1));
  }
  const double bound = 2.0 * (2 * n - 1) * (tension + weight) / k;
  std::cout << "  length change " << worst / l0 << " (chords), " << arc_worst / 0.1 << " (arc length); spring bound "
            << bound / l0 << " for a tension up to " << tension << " N\n";
  EXPECT_LE(worst, bound);
}

TEST(SlidingPoint, SaveAndRestoreIncludeTheAbscissa) {
  // s(t) and ṡ(t) live in the scene state (after the points): a restored state replays bit
  // for bit, and RK4's stage states carry them too.
  auto scene = test::loadConstraintScene(pulledThroughHole(0.5, 0.025, 1e-4));
  for (int k = 0; k < 6000; ++k) ASSERT_TRUE(scene->step().ok);
  const SceneState saved = scene->state();
  EXPECT_EQ(saved.q.size(), 3 * scene->dofPointCount() + 1);
  EXPECT_NE(hole(*scene).abscissa(saved), 0.5);
  for (int k = 0; k < 2000; ++k) ASSERT_TRUE(scene->step().ok);
  const SceneState first = scene->state();
  scene->setState(saved);
  for (int k = 0; k < 2000; ++k) ASSERT_TRUE(scene->step().ok);
  EXPECT_EQ(scene->state().q, first.q);
  EXPECT_EQ(scene->state().v, first.v);
}

TEST(SlidingPoint, ReleasedWhenTheThreadSlidesOutOfTheHole) {
  // Hole 1.5 cm from the tail, grip pulled 4 cm: the tail goes through, s leaves [0, 1], the
  // constraint is released and the run goes on (the violation no longer lists it).
  auto scene = test::loadConstraintScene(pulledThroughHole(0.15, 0.04, 1e-4));
  const auto& h = hole(*scene);
  int released_at = -1;
  for (int k = 0; k < 30000; ++k) {
    ASSERT_TRUE(scene->step().ok);
    if (released_at < 0 && !h.active()) released_at = k;
    // (The step in which s crosses 0 ends with the hole past the thread's end; the release
    // takes effect at the next step.)
    if (h.abscissa(scene->state()) >= 0.0) {
      ASSERT_LE(h.gap(scene->state()).norm(), 1e-8);
    }
  }
  ASSERT_GE(released_at, 0) << "the thread should have slid out";
  EXPECT_LT(h.abscissa(scene->state()), 0.0);
  EXPECT_EQ(scene->constraintViolation(scene->state()).size(), 3);  // the grip only
}

TEST(SlidingPoint, FrictionSlowsTheSliding) {
  // A thread hanging through a hole at s = 0.35 (no grip): the longer side wins and the
  // thread runs through like a rope over a pulley; viscous friction along the tangent slows
  // it (and only dissipates: F·u = −η (t̂·u)² <= 0).
  auto slide = [](double friction) {
    ConstraintThread t;
    t.control_points = 10;
    t.viscous_damping = 0.0;
    t.constraints = {json{{"type", "SlidingPointConstraint"}, {"abscissa", 0.35}, {"friction", friction}}};
    auto scene = test::loadConstraintScene(test::constraintScene({t}));
    for (int k = 0; k < 2000; ++k) EXPECT_TRUE(scene->step().ok);
    return hole(*scene).abscissa(scene->state());
  };
  const double free = slide(0.0), braked = slide(2e-4);
  EXPECT_LT(free, 0.35 - 0.02) << "the longer side (s > 0.35) pulls the thread through";
  EXPECT_GT(braked, free + 0.5 * (0.35 - free) * 0.1);
  EXPECT_LT(braked, 0.35);
}

/// A real 3-0 polypropylene suture (30 points, E = 2 GPa) through a hole at s = 0.5, drawn by a
/// grip at s = 1 from 0.2 to 2.2 s, under linearized backward Euler at 1 ms; `cuts` as the
/// DynamicSpline's "cuts" (none when null).
json implicitSutureThroughHole(const json& cuts = nullptr) {
  json spline = {{"type", "DynamicSpline"},
                 {"control_points", {{"from", {0, 0, 0}}, {"to", {0.1, 0, 0}}, {"count", 30}}},
                 {"radius", 1e-4},
                 {"density", 910}};
  if (!cuts.is_null()) spline["cuts"] = cuts;
  json thread = {{"name", "thread"},
                 {"components",
                  {spline,
                   {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}},
                   {{"type", "ParametricBending"}, {"youngs_modulus", 2e9}},
                   {{"type", "ViscousDamping"}, {"coefficient", 0.5}},
                   {{"type", "SlidingPointConstraint"}, {"name", "hole"}, {"abscissa", 0.5}},
                   {{"type", "FixedPointConstraint"},
                    {"name", "grip"},
                    {"abscissa", 1.0},
                    {"interpolation", "smooth"},
                    {"path",
                     {{{"time", 0.2}, {"position", {0.1, 0.0, 0.0}}},
                      {{"time", 2.2}, {"position", {0.125, 0.0, 0.01}}}}}}}}};
  return {{"name", "implicit sliding"},
          {"dt", 1e-3},
          {"gravity", {-3.0, 0.0, 0.0}},
          {"integrator", {{"type", "ImplicitEuler"}}},
          {"constraint_solver", {{"type", "LagrangeMultiplierSolver"}}},
          {"nodes", {thread}}};
}

TEST(SlidingPoint, RealSutureIsPulledThroughUnderImplicitEulerAt1ms) {
  // The same pull on a real 3-0 polypropylene suture (radius 0.1 mm, 910 kg/m³, E = 2 GPa,
  // Green–Lagrange stretching and bending) under linearized backward Euler at dt = 1 ms, a step
  // 50× beyond the explicit stability limit of its stretching (ω_max h ≈ 50). The abscissa s is
  // advanced with the points (v_s += h s̈, s += h v_s) from the direct relation evaluated after
  // the constrained point accelerations of each Newton update.
  const Factory factory = app::makeFactory();  // ImplicitEuler is in every build: its absence fails the load
  const json document = implicitSutureThroughHole();
  auto scene = loadScene(document, "implicit sliding", factory);
  const auto& h = hole(*scene);
  double worst = 0.0;
  for (int k = 0; k < 3000; ++k) {
    const StepReport report = scene->step();
    ASSERT_TRUE(report.ok) << report.message;
    worst = std::max(worst, h.gap(scene->state()).norm());
  }
  std::cout << "  implicit Euler, 1 ms: |P(s) - P0| <= " << worst << " m, s from 0.5 to " << h.abscissa(scene->state())
            << "\n";
  // The hole holds the thread: the gap stays a small fraction of the thread's radius (0.1 mm).
  // Backward Euler's local position error is O(h² |Δa|) per step, removed by the Baumgarte
  // terms within a few steps; for a pull at ~1 cm/s through a thread of curvature <~ 100 /m this
  // is far below 1 µm, the bound used here (1 % of the radius).
  EXPECT_LE(worst, 1e-6);
  // The grip draws 2.5 cm of an inextensible 10 cm thread through: Δs ≈ −0.25, less the tail's swing.
  EXPECT_LT(h.abscissa(scene->state()), 0.5 - 0.15);
  EXPECT_TRUE(h.active());
}

TEST(SlidingPoint, ACutEndSlidesOutOfTheHoleInsteadOfPassingToTheOtherStrand) {
  // The implicit suture above, cut at s = 0.42 at the start: the grip draws the thread through the
  // hole (s falls from 0.5), the cut end reaches the hole and slides out — the constraint is
  // released there, within twice a step's sliding of the cut, and stays released to the end,
  // although s, no longer held, runs on past the cut into the other strand's range.
  const Factory factory = app::makeFactory();
  const json document = implicitSutureThroughHole({{{"time", 0.0}, {"abscissa", 0.42}}});
  auto scene = loadScene(document, "implicit sliding, cut", factory);
  const auto& h = hole(*scene);
  int released_at = -1;
  double s_at_release = 0.0, previous = h.abscissa(scene->state());
  for (int k = 0; k < 3000; ++k) {
    const double before = h.abscissa(scene->state());
    ASSERT_TRUE(scene->step().ok) << k;
    if (released_at < 0 && !h.active()) {
      released_at = k;
      s_at_release = before;
      previous = before - h.abscissa(scene->state());  // the last step's slide
    }
    if (released_at >= 0) {
      EXPECT_FALSE(h.active()) << "held again at step " << k;
    }
  }
  ASSERT_GE(released_at, 0) << "the cut end should have reached the hole";
  EXPECT_GE(s_at_release, 0.42);
  EXPECT_LE(s_at_release - 0.42, 3.0 * std::abs(previous) + 1e-12);  // within twice a step's slide (+ ṡ's change)
}

// Redundant constraints: two sliding points at one abscissa give identical rows and a singular
// system. Its NaN abscissas used to index the basis out of range (a segmentation fault); the step
// now fails, names the solver and the cause, and rolls back.
TEST(SlidingPoint, RedundantHolesAreReportedAndRolledBack) {
  ConstraintThread t;
  t.constraints = {json{{"type", "SlidingPointConstraint"}, {"abscissa", 0.3}},
                   json{{"type", "SlidingPointConstraint"}, {"abscissa", 0.3}},
                   json{{"type", "FixedPointConstraint"}, {"abscissa", 0.5}}};
  auto scene = loadScene(test::constraintScene({t}), "redundant", app::makeFactory());
  const SceneState start = scene->state();
  const StepReport report = scene->step();
  ASSERT_FALSE(report.ok);
  EXPECT_NE(report.message.find("LagrangeMultiplierSolver"), std::string::npos) << report.message;
  EXPECT_NE(report.message.find("singular"), std::string::npos) << report.message;
  EXPECT_EQ(scene->state().time, start.time);
  EXPECT_TRUE(scene->state().q == start.q);
}

}  // namespace
}  // namespace filum
