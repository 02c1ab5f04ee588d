// Drift of every constraint type over 10^5 steps (10 s), with and without Baumgarte
// stabilization (paper §4; talk 002 "Lagrange multipliers + Baumgarte scheme").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>

#include "filum/core/scene.hpp"
#include "support/constraint_scenes.hpp"

namespace filum {
namespace {

using nlohmann::json;
using test::ConstraintThread;

struct Case {
  std::string name;
  std::vector<ConstraintThread> threads;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  auto fixedStart = json{{"type", "FixedPointConstraint"}, {"abscissa", 0.0}};
  {
    ConstraintThread t;
    t.constraints = {fixedStart};
    out.push_back({"fixed point", {t}});
  }
  {
    ConstraintThread t;
    t.constraints = {json{{"type", "FixedPointConstraint"}, {"abscissa", 0.0}, {"interpolation", "smooth"},
                          {"path", {{{"time", 1.0}, {"position", {0.0, 0.0, 0.0}}},
                                    {{"time", 3.0}, {"position", {0.01, 0.02, 0.01}}},
                                    {{"time", 5.0}, {"position", {0.0, 0.01, 0.0}}}}}}};
    out.push_back({"fixed point on a smooth scripted path", {t}});
  }
  {
    ConstraintThread t;
    t.constraints = {fixedStart, json{{"type", "PointOnAxisConstraint"}, {"abscissa", 1.0}, {"axis", {0, 1, 0}}}};
    out.push_back({"point on axis", {t}});
  }
  {
    ConstraintThread t;
    t.constraints = {fixedStart, json{{"type", "PointOnPlaneConstraint"}, {"abscissa", 1.0}, {"normal", {0, 0, 1}}}};
    out.push_back({"point on plane", {t}});
  }
  {
    ConstraintThread t;
    t.constraints = {json{{"type", "ClampConstraint"}, {"abscissa", 0.0}}};
    out.push_back({"clamp", {t}});
  }
  {
    ConstraintThread t;
    t.constraints = {fixedStart, json{{"type", "SlidingPointConstraint"}, {"abscissa", 0.3}, {"friction", 1e-5}}};
    out.push_back({"sliding point", {t}});
  }
  {
    ConstraintThread a, b;
    a.control_points = b.control_points = 6;
    a.length = b.length = 0.05;
    b.name = "second";
    b.origin = {0.05, 0.0, 0.0};
    a.constraints = {fixedStart, json{{"type", "SplineJunctionConstraint"}, {"other", "second"}, {"continuity", 2}}};
    out.push_back({"C2 junction", {a, b}});
  }
  {
    ConstraintThread a, b;
    a.control_points = b.control_points = 6;
    a.length = b.length = 0.05;
    b.name = "second";
    b.origin = {0.05, 0.0, 0.0};
    a.constraints = {fixedStart};
    b.constraints = {json{{"type", "FixedPointConstraint"}, {"abscissa", 0.0},
                          {"target", {{"object", "thread"}, {"abscissa", 1.0}}}}};
    out.push_back({"fixed point attached to another thread", {a, b}});
  }
  return out;
}

/// Largest violation in each tenth of a run of `steps` steps of RK4 (dt = 1e-4 s) under a
/// tilted gravity (so that every constrained point is pushed along and across its constraint).
std::vector<double> run(const Case& c, std::optional<double> omega, long steps) {
  json document = test::constraintScene(c.threads, 1e-4, "RungeKutta4", {0.0, -3.0, -9.81});
  if (omega)
    for (auto& node : document["nodes"])
      for (auto& component : node["components"])
        if (component["type"].get<std::string>().find("Constraint") != std::string::npos)
          component["stabilization"] = *omega;
  auto scene = test::loadConstraintScene(document);
  std::vector<double> tenths;
  for (int k = 0; k < 10; ++k) tenths.push_back(test::maxViolationOver(*scene, steps / 10));
  return tenths;
}

double maxOf(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

TEST(ConstraintDrift, StabilizationHoldsEveryConstraintBelow1e8OverTenToTheFiveSteps) {
  // With the Baumgarte terms (ω = 0.1/dt = 1000/s) the violation is what RK4 leaves in one
  // step, O(dt⁵) times the derivatives of g, pulled back at once: the bound 1e-8 m of the
  // issue holds with orders of magnitude to spare (measured: ≤ 2e-10, the smooth scripted
  // path's acceleration jumps at keyframes; round-off level, ~1e-17, for the others).
  //
  // Without them (ω = 0) the rows still enforce g̈ exactly, and what happens depends on g:
  //  - g linear in q with a fixed target (fixed point, axis, plane, clamp, junction,
  //    attachment): every Runge-Kutta method preserves linear invariants exactly, so only
  //    round-off accumulates — but it does accumulate (velocity-level round-off integrates to a
  //    position drift growing like t², from 1e-14 m in the first second to 1e-12 .. 1e-10 m);
  //  - a time-dependent target (the scripted path: RK4's local error on Ẍ(t), and O(dt²) at the
  //    path's acceleration jumps) or a g nonlinear in the DOFs (the sliding point's P(s(t))):
  //    truncation errors accumulate and never decay (1e-7 .. 3e-6 m after 10 s).
  // Either way the drift grows (last tenth of the run > 2 × first tenth) and ends far above
  // the stabilized violation: stabilization is what holds the constraints.
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const std::vector<double> held = run(c, std::nullopt, 100000);
    const std::vector<double> drift = run(c, 0.0, 100000);
    std::cout << "  " << c.name << ": stabilized max " << maxOf(held) << " m; without stabilization " << drift.front()
              << " m (first second) -> " << drift.back() << " m (last second)\n";
    EXPECT_LE(maxOf(held), 1e-8);
    // Drift, not divergence: an unstabilized run that blew up would prove nothing.
    ASSERT_TRUE(std::isfinite(maxOf(drift)));
    EXPECT_GT(drift.back(), 2.0 * drift.front());
    EXPECT_GT(drift.back(), 10.0 * maxOf(held));
  }
}

}  // namespace
}  // namespace filum
