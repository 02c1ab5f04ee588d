// A haptic device on an instrument's hub (haptics/hub_device.hpp), against statics worked out by
// hand: a rod twisted between its hub and a clamped far end gives the hand back T = G J ψ / L
// about the stylus's axis; a rod hanging from its hub pulls the hand down with its weight
// ρ A L g along the introducer; strokes with the grip released in between add up to the
// insertion; every field refused at its JSON path.
#include <gtest/gtest.h>

#include <cmath>

#include "filum/collision/register_components.hpp"
#include "filum/constraints/register_components.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/haptics/hub_device.hpp"
#include "filum/mechanics/framed_chain.hpp"
#include "filum/mechanics/register_components.hpp"

namespace filum::haptics {
namespace {

using nlohmann::json;

// The rod: 0.2 m, radius 0.5 mm, E = 2 GPa, ν = 0.3, 4000 kg/m³ (a guidewire's core), 21 nodes.
constexpr double kLength = 0.2, kRadius = 5e-4, kModulus = 2e9, kPoisson = 0.3, kDensity = 4000.0;

/// A rod from the origin along `direction` (the introducer's axis), its hub at s = 0 held by a
/// FixedPointConstraint and a RodEndFrame; `clamped`: its far end held the same way.
json rodScene(const Vec3& direction, bool clamped, const json& gravity, const json& device) {
  const Vec3 end = kLength * direction;
  json components = json::array(
      {{{"type", "FramedChain"}, {"nodes", {{"from", {0, 0, 0}}, {"to", {end.x(), end.y(), end.z()}}, {"count", 21}}},
        {"radius", kRadius}, {"density", kDensity}},
       {{"type", "ChainElasticity"}, {"youngs_modulus", kModulus}, {"poisson_ratio", kPoisson}},
       {{"type", "RodEndFrame"}, {"end", "start"}},
       {{"type", "FixedPointConstraint"}, {"abscissa", 0.0}},
       {{"type", "ViscousDamping"}, {"coefficient", 20.0}}});
  if (clamped) {
    components.push_back({{"type", "RodEndFrame"}, {"end", "end"}});
    components.push_back({{"type", "FixedPointConstraint"}, {"abscissa", 1.0}});
  }
  return json{{"name", "hub device test"}, {"dt", 1e-3}, {"duration", 1.0}, {"gravity", gravity},
              {"integrator", {{"type", "ImplicitEuler"}}}, {"constraint_solver", {{"type", "LagrangeMultiplierSolver"}}},
              {"nodes", json::array({{{"name", "wire"}, {"components", components}}})},
              {"navigation", {{"instrument", "wire"}, {"device", device}}}};
}

/// A ScriptedDevice block with these waypoints (device frame = scene frame).
json scripted(const json& waypoints, double peak_torque = 0.1) {
  return json{{"device", {{"type", "ScriptedDevice"}, {"model", "Touch"}, {"waypoints", waypoints}}},
              {"limits", {{"peak_torque", peak_torque}}}};
}

struct HubRun {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<HubDevice> hub;
  explicit HubRun(const json& document) {
    Factory factory;
    mechanics::register_components(factory);
    constraints::register_components(factory);
    collision::register_components(factory);
    scene = loadScene(document, "hub.json", factory);
    hub = HubDevice::fromScene(document, "hub.json", *scene, document["duration"].get<double>());
  }
  /// Steps until time t (s) with the device around each; false when a step failed.
  bool runUntil(double t) {
    while (scene->state().time < t - 0.5 * scene->settings().dt) {
      hub->beforeStep(*scene);
      if (!scene->step().ok) return false;
      hub->afterStep(*scene);
    }
    return true;
  }
  /// The newest servo tick (it runs at the step's start: the model of the step before).
  ServoSample lastTick() {
    hub->session().servo().runLockstepUntil(scene->state().time);
    return hub->session().servo().log().back();
  }
};

TEST(HubDevice, ATwistedRodGivesTheHandItsTorqueAboutTheStylusAxis) {
  // Grip from the start; the stylus turned by ψ = 0.5 rad over 0.1–0.5 s, then held: the hub turns
  // the rod's start by ψ against its clamped end (which has a RodEndFrame of its own: the device
  // must turn the start's). The discrete rod's twist compliance is exact for a uniform twist (the
  // end half-segments and the interior nodes' lengths add up to L, docs/rods.md), so at rest the
  // held frame bears T = G J ψ / L, and segment j's frame has turned by ψ (1 − (j + ½)/n), n = 20
  // segments. What is left after 0.5 s at rest: the transient of the twist modes, whose lowest,
  // ω = (π/L)√(G/ρ) ≈ 6.9e3 rad/s, backward Euler damps by 1/sqrt(1 + (ω h)²) ≈ 0.14 a step (h = 1 ms),
  // far below round-off after 500 steps, and the round-off of log(Rᵀ R) (ε ψ). The tolerance,
  // 1e-9 relative, is above both (measured: 2e-15).
  const double psi = 0.5;
  HubRun run(rodScene(Vec3::UnitZ(), true, {0, 0, 0},
                      scripted({{{"time", 0.0}, {"position", {0, 0, 0}}, {"buttons", 1}},
                                {{"time", 0.1}, {"position", {0, 0, 0}}, {"buttons", 1}},
                                {{"time", 0.5}, {"position", {0, 0, 0}}, {"buttons", 1}, {"roll", psi}},
                                {{"time", 1.0}, {"position", {0, 0, 0}}, {"buttons", 1}}})));
  const auto& chain = dynamic_cast<const mechanics::FramedChain&>(*run.scene->bodies().front()->curve());
  const Eigen::Quaterniond first0 = chain.orientation(run.scene->state().q, 0);
  const Eigen::Quaterniond last0 = chain.orientation(run.scene->state().q, 19);
  ASSERT_TRUE(run.runUntil(1.0));
  // The turn of a segment's frame about the rod's axis (+z) since the start.
  const auto turned = [&](const Eigen::Quaterniond& now, const Eigen::Quaterniond& before) {
    const Eigen::Quaterniond r = now * before.conjugate();
    return 2.0 * std::atan2(r.z(), r.w());
  };
  EXPECT_NEAR(turned(chain.orientation(run.scene->state().q, 0), first0), psi * (1.0 - 0.5 / 20), 1e-9 * psi);
  EXPECT_NEAR(turned(chain.orientation(run.scene->state().q, 19), last0), psi * 0.5 / 20, 1e-9 * psi);
  const double G = kModulus / (2.0 * (1.0 + kPoisson)), J = M_PI * std::pow(kRadius, 4) / 2.0;
  const double expected = G * J * psi / kLength;  // N·m
  EXPECT_NEAR(run.hub->hub().roll(*run.scene), psi, 1e-15);
  // The held frame turns the rod by +ψ about a₀ = +z: it bears +T; the hand, turning it, feels −T.
  EXPECT_NEAR(run.hub->hub().torque(*run.scene), expected, 1e-9 * expected);
  EXPECT_NEAR(run.hub->handTorque(), -expected, 1e-9 * expected);
  const ServoSample tick = run.lastTick();
  EXPECT_NEAR(tick.roll, psi, 1e-15);
  EXPECT_NEAR(tick.torque_sent, -expected, 1e-9 * expected);  // within the 0.1 N·m peak
  EXPECT_EQ(run.hub->strokes(), 1);
}

TEST(HubDevice, ARodHangingFromItsHubPullsTheHandDownWithItsWeight) {
  // The rod hangs from its hub along a₀ = −z: at rest the hub bears its whole weight m g, m = ρ A L
  // (the chain's point masses add up to it), and the hand feels F = −(f·a₀) a₀ = −m g ẑ. Left after
  // 1 s: the transient of the axial modes that the weight excites (the rod starts straight along
  // gravity: the bending modes are not excited but by round-off), the lowest at
  // ω = (π/2L)√(E/ρ) ≈ 5.6e3 rad/s, which backward Euler damps by 1/sqrt(1 + (ω h)²) ≈ 0.18 a step:
  // nothing after a thousand. Tolerance 1e-6 relative, far above that (measured: 3e-13).
  HubRun run(rodScene(-Vec3::UnitZ(), false, {0, 0, -9.81},
                      scripted({{{"time", 0.0}, {"position", {0, 0, 0}}, {"buttons", 1}},
                                {{"time", 1.0}, {"position", {0, 0, 0}}, {"buttons", 1}}})));
  ASSERT_TRUE(run.runUntil(1.0));
  const double weight = kDensity * M_PI * kRadius * kRadius * kLength * 9.81;  // N
  EXPECT_TRUE(run.hub->handForce().isApprox(Vec3(0, 0, -weight), 1e-6)) << run.hub->handForce().transpose();
  const ServoSample tick = run.lastTick();
  EXPECT_TRUE(tick.sent.isApprox(Vec3(0, 0, -weight), 1e-6)) << tick.sent.transpose();
}

TEST(HubDevice, StrokesWithTheGripReleasedInBetweenAddUp) {
  // Two strokes of 2 cm along a₀ = +z; between them the stylus goes back with the button up. The
  // hub's target is set from the stylus by arithmetic: 4 cm to round-off. The hub itself follows
  // within the constraint's error, which Baumgarte's critically damped term (ω = 0.1/dt = 100/s)
  // shrinks by (1 + ω t) e^(−ω t) ≈ 3e-12 over the 0.3 s held at the end: a lag of even a
  // segment (10 mm) is then 3e-14 m; asked within 1e-9 m.
  HubRun run(rodScene(Vec3::UnitZ(), false, {0, 0, 0},
                      scripted({{{"time", 0.0}, {"position", {0, 0, 0}}, {"buttons", 1}},
                                {{"time", 0.3}, {"position", {0, 0, 0.02}}, {"buttons", 0}},
                                {{"time", 0.5}, {"position", {0, 0, 0}}, {"buttons", 1}},
                                {{"time", 0.7}, {"position", {0, 0, 0.02}}, {"buttons", 1}},
                                {{"time", 1.0}, {"position", {0, 0, 0.02}}, {"buttons", 1}}})));
  ASSERT_TRUE(run.runUntil(0.4));
  const double first = run.hub->hub().insertion(*run.scene);
  EXPECT_NEAR(first, 0.02, 1e-12);  // let go at 0.3 s: the hub stays while the hand goes back
  EXPECT_FALSE(run.hub->gripping());
  EXPECT_EQ(run.hub->handForce(), Vec3::Zero());  // nothing felt without the grip
  ASSERT_TRUE(run.runUntil(1.0));
  EXPECT_NEAR(run.hub->hub().insertion(*run.scene), 0.04, 1e-12);
  EXPECT_EQ(run.hub->strokes(), 2);
  const CurveBody& wire = *run.scene->bodies().front()->curve();
  EXPECT_NEAR(wire.position(run.scene->state().q, 0.0).z(), 0.04, 1e-9);
}

TEST(HubDevice, EveryFieldIsRefusedAtItsJsonPath) {
  const json device = scripted({{{"time", 0.0}, {"position", {0, 0, 0}}}});
  const auto refused = [&](json document, const std::string& where) {
    try {
      HubRun run(document);
      ADD_FAILURE() << "accepted; expected a refusal at " << where;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
    }
  };
  json unknown = rodScene(Vec3::UnitZ(), false, {0, 0, 0}, device);
  unknown["navigation"]["device"]["instrument"] = "catheter";
  refused(unknown, "/navigation/device/instrument");
  json no_hub = rodScene(Vec3::UnitZ(), false, {0, 0, 0}, device);
  no_hub["nodes"][0]["components"].erase(3);  // the FixedPointConstraint at s = 0
  refused(no_hub, "/navigation/instrument");   // where the instrument was named
  json two = rodScene(Vec3::UnitZ(), false, {0, 0, 0}, device);
  two["haptics"] = {{"device", {{"type", "ScriptedDevice"}}}};
  refused(two, "/navigation/device/device");  // "expected one haptic device a scene ..."
  json button = rodScene(Vec3::UnitZ(), false, {0, 0, 0}, device);
  button["navigation"]["device"]["button"] = 17;
  refused(button, "/navigation/device/button");
  json scale = rodScene(Vec3::UnitZ(), false, {0, 0, 0}, device);
  scale["navigation"]["device"]["roll_scale"] = 0.0;
  refused(scale, "/navigation/device/roll_scale");
  json typo = rodScene(Vec3::UnitZ(), false, {0, 0, 0}, device);
  typo["navigation"]["device"]["rol_scale"] = 1.0;
  refused(typo, "/navigation/device");
  json torque = rodScene(Vec3::UnitZ(), false, {0, 0, 0}, device);
  torque["navigation"]["device"]["limits"]["peak_torque"] = -1.0;
  refused(torque, "/navigation/device/limits/peak_torque");
}

TEST(HubDevice, AHubThatLetsGoIsDrivenNoMoreAndTheRunGoesOn) {
  // The hub's constraint released at 0.3 s (its "release_at"): the next steps cannot steer it; the
  // device says so once and the run goes on, the hand feeling nothing.
  json document = rodScene(Vec3::UnitZ(), false, {0, 0, 0},
                           scripted({{{"time", 0.0}, {"position", {0, 0, 0}}, {"buttons", 1}},
                                     {{"time", 1.0}, {"position", {0, 0, 0.02}}, {"buttons", 1}}}));
  document["nodes"][0]["components"][3]["release_at"] = 0.3;
  HubRun run(document);
  ASSERT_TRUE(run.runUntil(0.6));
  EXPECT_NE(run.hub->lost().find("the hub cannot be driven any more"), std::string::npos) << run.hub->lost();
  EXPECT_NE(run.hub->summary().find("cannot be driven"), std::string::npos);
  EXPECT_FALSE(run.hub->gripping());
  EXPECT_EQ(run.hub->handForce(), Vec3::Zero());
}

TEST(HubDevice, AStylusGoneQuietLeavesTheHubWhereItIs) {
  // A servo at 100 Hz with a watchdog of 5 ms: after each sample the hub moves on at the stylus's
  // speed, and once the stylus has been quiet for longer than the watchdog (at the step 5 to 6 ms
  // after the sample) it is held where it is and the grip ends; the next sample, 10 ms after the
  // last, is a new grip from where the stylus then is. The stylus moves 2 cm in 1 s with the
  // button held: the hub follows for 5 to 6 ms of every 10, 1 to 1.2 cm; with samples at every
  // step it would follow all 2 cm. Asked between 40 % and 70 % of it.
  json document = rodScene(Vec3::UnitZ(), false, {0, 0, 0},
                           scripted({{{"time", 0.0}, {"position", {0, 0, 0}}, {"buttons", 1}},
                                     {{"time", 1.0}, {"position", {0, 0, 0.02}}, {"buttons", 1}}}));
  document["navigation"]["device"]["rate"] = 100;
  document["navigation"]["device"]["watchdog"] = 0.005;
  HubRun run(document);
  ASSERT_TRUE(run.runUntil(1.0));
  EXPECT_GT(run.hub->hub().insertion(*run.scene), 0.4 * 0.02);
  EXPECT_LT(run.hub->hub().insertion(*run.scene), 0.7 * 0.02);
  EXPECT_GT(run.hub->strokes(), 90);  // a new grip at (nearly) every one of the 100 samples
}

}  // namespace
}  // namespace filum::haptics
