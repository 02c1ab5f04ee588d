// apps/scenes/coil.json as a physicist would check the delivery: the coil is pushed
// through the microcatheter (a ChannelConstraint) at the delivery wire's speed v, so the length of
// coil in the aneurysm grows by v t — the coil is not lost or made along the way — while the part
// in the channel stays on its centre line and the part out of it stays in the lumen.
//
// Tolerances.
// - Length in the aneurysm against v t: the metric cuts the coil's centre line into 512 chords and
//   counts those whose midpoint is inside (coil_packing.hpp): off by at most one chord where the
//   coil enters the neck, 60 mm / 512 (twice: at t = 0 and at t); the coil's axial strain under
//   the push, at most (friction and contact forces below 0.01 N) / (E A = 0.84 N): 1.2 %, of v t.
// - On the centre line: the rows hold the points across the channel at the acceleration level,
//   built at each step's start. The channel's bend is a polyline of segments Δs = 0.25 mm turning
//   by Δθ = Δs/R (R = 2 mm, the tip's bend): a node that crosses a vertex within a step is held
//   across the segment it was on, and ends up to v h sin Δθ off the next one, which the
//   stabilization then removes (by 1 − (ωh)² a step at ωh = 0.5, the scene's ω = 500/s). Added
//   to that: the centripetal acceleration the rows leave out, v²/R, which Baumgarte's ω² g
//   balances at v²/(R ω²) (critically damped: no overshoot).
// - At the tip: the support's rows leave out the crossing point's P″ σ̇*², κ v² for the coil's
//   curvature κ = 333 rad/m there, balanced at κ v²/ω²; with the same vertex term (the nodes it
//   lies between are held up to the channel's last vertices).
// - In the lumen: never deeper in the wall than a tenth of the coil's radius (coil_test.cpp).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "filum/all_components.hpp"
#include "filum/collision/vessel_lumen_obstacle.hpp"
#include "filum/constraints/channel_constraint.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/haptics/navigation_metrics.hpp"
#include "support/navigation_scene_run.hpp"

namespace filum {
namespace {

constexpr double kPushSpeed = 0.02;  // m/s (apps/tools/make_coil_delivery_scene.py)
constexpr double kBendRadius = 2e-3;  // m, the microcatheter's tip bend (the same)
constexpr double kSegment = 2.5e-4;   // m, its polyline's segments (the same)
constexpr double kCoilCurvature = 333.2;  // 1/m, the coil's rest curvature (the same)

TEST(CoilDelivery, TheCoilGoesInAtThePushersSpeedAndStaysInTheLumen) {
  test::NavigationSceneRun run("coil.json");
  const auto& scene = run.scene;
  const auto& metrics = run.metrics;
  ASSERT_NE(metrics, nullptr);
  ASSERT_NE(metrics->packing(), nullptr);
  const CurveBody& coil = *scene->bodies()[0]->curve();
  const geometry::VesselTree& tree = metrics->lumen().tree();
  const auto* channel = dynamic_cast<const constraints::ChannelConstraint*>(scene->constraints().back());
  ASSERT_NE(channel, nullptr);
  const double r = coil.radius(), dt = scene->settings().dt;
  const double omega = 500.0;  // 1/s, the channel's "stabilization"
  const double start = metrics->packing()->lengthInside(coil, scene->state().q);
  const double chord = 0.06 / 512;
  double worst_length = 0.0, worst_axis = 0.0, worst_tip = 0.0, deepest = 0.0;
  const long steps = std::lround(0.6 / dt);  // 12 mm of coil pushed out
  for (long k = 1; k <= steps; ++k) {
    const StepReport report = run.step();
    ASSERT_TRUE(report.ok) << report.message;
    if (k % 20) continue;
    const SceneState& s = scene->state();
    const double pushed = kPushSpeed * s.time;
    const double grown = metrics->packing()->lengthInside(coil, s.q) - start;
    worst_length = std::max(worst_length, std::abs(grown - pushed) / (2 * chord + 0.012 * pushed));
    // The channel's rows (its violation: two per point held, the tip's last; the delivery wire's
    // fixed point first).
    const VecX g = scene->constraintViolation(s);
    worst_axis = std::max(worst_axis, g.tail(channel->violationCount()).head(channel->violationCount() - 2).lpNorm<Eigen::Infinity>());
    worst_tip = std::max(worst_tip, g.tail(2).lpNorm<Eigen::Infinity>());
    for (int i = 0; i <= 960; ++i) {
      const Vec3 x = coil.position(s.q, i / 960.0);
      if (x.z() < -8e-3) continue;  // the channel below the parent's open inlet: outside the vessel data
      deepest = std::max(deepest, test::wallDepth(tree.sample(x, tree.maxRadius()), r));
    }
  }
  const double v = kPushSpeed, kick = v * dt * std::sin(kSegment / kBendRadius);
  const double allowed_axis = v * v / (kBendRadius * omega * omega) + kick;
  const double allowed_tip = kCoilCurvature * v * v / (omega * omega) + kick;
  std::printf("  length in the aneurysm against v t: worst %.2f of its tolerance; off the centre line %.4g m (%.4g "
              "allowed), at the tip %.2g m (%.2g allowed); deepest in the wall %.3f r\n", worst_length, worst_axis,
              allowed_axis, worst_tip, allowed_tip, deepest);
  EXPECT_LE(worst_length, 1.0);
  EXPECT_LE(worst_axis, allowed_axis);
  EXPECT_LE(worst_tip, allowed_tip);
  EXPECT_LT(deepest, 0.1);
}

}  // namespace
}  // namespace filum
