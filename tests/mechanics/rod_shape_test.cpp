// What instruments need of a rod (chain_elasticity.hpp, framed_chain.hpp, rod_end_frame.hpp): a
// rest shape (a coil's helix given as the initial nodes, a J-tip given as curvature by
// abscissa), material and cross-section changing along the rod, and a hub turned by the hand —
// each against the mechanics it must reproduce. Statics by support/rod_statics.hpp (node 0
// held, RodEndFrame holding the frame).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "filum/all_components.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/geometry/rotation_vector.hpp"
#include "filum/mechanics/chain_elasticity.hpp"
#include "filum/mechanics/framed_chain.hpp"
#include "support/rod_statics.hpp"

namespace filum {
namespace {

using nlohmann::json;
using mechanics::FramedChain;

using namespace test::rod;  // kLength, kRadius, kDensity
constexpr double kModulus = 3e7;  // polyurethane

std::unique_ptr<Scene> load(const json& chain, const json& elasticity, const json& more = json::array(),
                            double gravity = 0.0) {
  json components = {chain, elasticity};
  for (const json& c : more) components.push_back(c);
  const json document = {{"dt", 5e-6},
                         {"duration", 1.0},
                         {"gravity", {0, 0, -gravity}},
                         {"integrator", {{"type", "RungeKutta4"}}},
                         {"nodes", {{{"name", "rod"}, {"components", components}}}}};
  auto scene = loadScene(document, "rod shape test", app::makeFactory());
  scene->init();
  return scene;
}

json straightRod(int nodes) {
  return {{"type", "FramedChain"},
          {"nodes", {{"from", {0, 0, 0}}, {"to", {kLength, 0, 0}}, {"count", nodes}}},
          {"radius", kRadius},
          {"density", kDensity}};
}

const FramedChain& chainOf(const Scene& scene) { return dynamic_cast<const FramedChain&>(*scene.bodies().front()); }

Vec3 tipOf(const Scene& scene, const SceneState& s) {
  return chainOf(scene).block(s.q).row(chainOf(scene).pointCount() - 1).transpose();
}

TEST(RodShape, AHelixGivenAsItsRestShapeStaysAtRest) {
  // A coil (radius 5 mm, pitch 2 mm, three turns, 91 nodes) whose initial nodes are its rest
  // shape: every stretch and turn is at rest (the same operations give φ and φ̄), and d3 − t of
  // the parallel-transported frames is the round-off of their construction, a product of up to
  // 90 quaternions: at most 90 ε ≈ 1e-14. The shear force on the points is κGA (d3 − t) up to
  // the projection (the 1/|e| of ∂t/∂e cancels the l of the energy), so no force exceeds
  // 1e-14 κGA. Then 2000 RK4 steps without gravity: nothing moves (such forces over 1e-2 s move
  // a node by less than 1e-12 m).
  const int nodes = 91;
  json list = json::array();
  for (int i = 0; i < nodes; ++i) {
    const double a = 2.0 * std::numbers::pi * 3.0 * i / (nodes - 1);
    list.push_back({5e-3 * std::cos(a), 5e-3 * std::sin(a), 2e-3 * a / (2.0 * std::numbers::pi)});
  }
  json chain = straightRod(nodes);
  chain["nodes"] = list;
  auto scene = load(chain, {{"type", "ChainElasticity"}, {"youngs_modulus", kModulus}, {"rest_shape", "initial"}});
  const auto& elasticity = dynamic_cast<const mechanics::ChainElasticity&>(*scene->forceFields().front());
  VecX B = VecX::Zero(scene->velocitySize());
  elasticity.addForce(scene->state(), B);
  EXPECT_LE(B.cwiseAbs().maxCoeff(), 1e-14 * elasticity.shearStiffness(0));
  const Points start = chainOf(*scene).block(scene->state().q);
  for (int k = 0; k < 2000; ++k) ASSERT_TRUE(scene->step().ok);
  EXPECT_LE((chainOf(*scene).block(scene->state().q) - start).cwiseAbs().maxCoeff(), 1e-12);
}

/// The J-tip: curvature κ about d2 over s ∈ [0.75, 1], straight before; tip where the rest shape
/// puts it: straight to L1 = 0.75 L along x, then an arc of radius 1/κ bending down (a turn about
/// d2 = y takes the tangent x towards −z).
Vec3 jTip(double kappa, double roll) {
  const double L1 = 0.75 * kLength, alpha = kappa * 0.25 * kLength;
  return {L1 + std::sin(alpha) / kappa, 0.0, -std::cos(roll) * (1.0 - std::cos(alpha)) / kappa};
}

json jTipElasticity(double kappa) {
  return {{"type", "ChainElasticity"},
          {"youngs_modulus", kModulus},
          {"spans", {{{"from", 0.75}, {"to", 1.0}, {"rest_curvature", {0.0, kappa}}}}}};
}

TEST(RodShape, AJTipTakesItsRestShapeAtSecondOrder) {
  // Unloaded and clamped, the rod takes its rest shape: the segments' directions are the exact
  // tangent at their middles (the rest turns integrate κ̄ exactly between middles), so the tip,
  // a midpoint-rule sum of chords, is second order in the segment length: within 1 % of the
  // arc's sagitta at 21 nodes, the error divided by 4 per halving (order within 0.25 of 2).
  const double kappa = (std::numbers::pi / 2.0) / (0.25 * kLength);  // a quarter turn over 5 cm
  std::vector<double> errors;
  for (const int nodes : {21, 41, 81}) {
    auto scene = load(straightRod(nodes), jTipElasticity(kappa), json::array({{{"type", "RodEndFrame"}}}));
    const SceneState s = test::equilibrium(*scene, 1);
    errors.push_back((tipOf(*scene, s) - jTip(kappa, 0.0)).norm() / (1.0 / kappa));
    std::cout << "  " << nodes << " nodes: tip " << tipOf(*scene, s).transpose() << ", exact "
              << jTip(kappa, 0.0).transpose() << ", error " << errors.back() << " of 1/κ\n";
  }
  EXPECT_LE(errors[0], 1e-2);
  EXPECT_NEAR(std::log2(errors[1] / errors[2]), 2.0, 0.25);
}

TEST(RodShape, TurningTheHubByHalfATurnFlipsTheJTip) {
  // The hub turned by π along a path (RodEndFrame "path", roll from 0 at t = 0 to π at t = 1 s,
  // followed here by equilibria at eight successive times): the twist carries the turn to the
  // tip, whose curl now points up (+z) — the mirror of the unturned tip.
  const double kappa = (std::numbers::pi / 2.0) / (0.25 * kLength);
  auto turned = load(straightRod(41), jTipElasticity(kappa),
                     json::array({{{"type", "RodEndFrame"},
                                   {"path", {{{"time", 0.0}, {"roll", 0.0}}, {{"time", 1.0}, {"roll", std::numbers::pi}}}}}}));
  auto plain = load(straightRod(41), jTipElasticity(kappa), json::array({{{"type", "RodEndFrame"}}}));
  SceneState s = test::equilibrium(*turned, 1);
  for (int k = 1; k <= 8; ++k) {
    s.time = k / 8.0;
    s = test::equilibrium(*turned, 1, s);
  }
  const Vec3 up = tipOf(*turned, s), down = tipOf(*plain, test::equilibrium(*plain, 1));
  std::cout << "  rolled tip " << up.transpose() << ", unrolled " << down.transpose() << '\n';
  // Mirror images about the plane z = 0 to the Newton tolerance (1e-13 m updates), 1e-12 m.
  EXPECT_NEAR(up.x(), down.x(), 1e-12);
  EXPECT_NEAR(up.z(), -down.z(), 1e-12);
  EXPECT_GT(up.z(), 0.5 * (1.0 - std::cos(kappa * 0.25 * kLength)) / kappa);
}

TEST(RodShape, AStiffShaftWithASoftThinTipDeflectsAsTheBeamEquationSays) {
  // E1, r1 on [0, L/2]; E2 = E1/10 and r2 = r1/2 on [L/2, L] (FramedChain and ChainElasticity
  // spans). End load P, small deflection: δ = P ∫ (L − s)² / EI(s) ds + P ∫ ds / κGA(s)
  // (Euler–Bernoulli with Timoshenko's shear term), here in closed form over the two halves.
  // The span ends fall on nodes; second order as above.
  const double E1 = kModulus, E2 = E1 / 10.0, r1 = kRadius, r2 = kRadius / 2.0, h = kLength / 2.0;
  const auto I = [](double r) { return std::numbers::pi * std::pow(r, 4) / 4.0; };
  const auto kGA = [](double E, double r) { return 0.9 * E / 3.0 * std::numbers::pi * r * r; };
  const double EI1 = E1 * I(r1), EI2 = E2 * I(r2);
  const double unit = (std::pow(kLength, 3) - std::pow(h, 3)) / (3.0 * EI1) + std::pow(h, 3) / (3.0 * EI2) +
                      h / kGA(E1, r1) + h / kGA(E2, r2);  // δ / P
  const double P = 1e-4 * kLength / unit;                // δ = 1e-4 L
  std::vector<double> errors;
  for (const int nodes : {21, 41, 81}) {
    json chain = straightRod(nodes);
    chain["spans"] = {{{"from", 0.5}, {"to", 1.0}, {"radius", r2}}};
    json elasticity = {{"type", "ChainElasticity"},
                       {"youngs_modulus", E1},
                       {"spans", {{{"from", 0.5}, {"to", 1.0}, {"youngs_modulus", E2}}}}};
    auto scene = load(chain, elasticity,
                      json::array({{{"type", "RodEndFrame"}}, {{"type", "PointLoad"}, {"abscissa", 1.0}, {"force", {0, 0, -P}}}}));
    const SceneState s = test::equilibrium(*scene, 1);
    errors.push_back(std::abs(-tipOf(*scene, s).z() - P * unit) / (P * unit));
    std::cout << "  " << nodes << " nodes: tip deflection error " << errors.back() << '\n';
  }
  EXPECT_LE(errors[0], 1e-2);
  EXPECT_NEAR(std::log2(errors[1] / errors[2]), 2.0, 0.25);
  // The mass follows the sections: ρ π (r1² + r2²) L / 2, to round-off.
  json chain = straightRod(21);
  chain["spans"] = {{{"from", 0.5}, {"to", 1.0}, {"radius", r2}}};
  auto scene = load(chain, {{"type", "ChainElasticity"}, {"youngs_modulus", E1}});
  EXPECT_NEAR(chainOf(*scene).mass(), kDensity * std::numbers::pi * (r1 * r1 + r2 * r2) * h, 1e-14 * chainOf(*scene).mass());
}

TEST(RodShape, RefusesShapesAndMaterialsThatDoNotFit) {
  const auto refused = [](const json& chain, const json& elasticity, const json& more, const std::string& fragment) {
    try {
      load(chain, elasticity, more);
      ADD_FAILURE() << "accepted " << elasticity.dump() << ' ' << more.dump();
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  const json base = {{"type", "ChainElasticity"}, {"youngs_modulus", kModulus}};
  json span_outside = base;
  span_outside["spans"] = {{{"from", 0.5}, {"to", 1.5}, {"youngs_modulus", 1e6}}};
  refused(straightRod(5), span_outside, json::array(), "/spans/0/to");
  json reversed = base;
  reversed["spans"] = {{{"from", 0.6}, {"to", 0.2}}};
  refused(straightRod(5), reversed, json::array(), "above 'from'");
  json both = base;
  both["rest_shape"] = "initial";
  both["rest_curvature"] = {1.0, 0.0};
  refused(straightRod(5), both, json::array(), "not both");
  json bad_curvature = base;
  bad_curvature["rest_curvature"] = {1.0};
  refused(straightRod(5), bad_curvature, json::array(), "/rest_curvature");
  refused(straightRod(5), base, json::array({{{"type", "RodEndFrame"}, {"path", {{{"direction", {1, 0, 0}}}}}}}),
          "/path/0/time");
  refused(straightRod(5), base,
          json::array({{{"type", "RodEndFrame"}, {"path", {{{"time", 1.0}, {"roll", 0.0}}, {{"time", 0.5}, {"roll", 1.0}}}}}}),
          "/path/1/time");
  refused(straightRod(5), base, json::array({{{"type", "RayleighDamping"}, {"stiffness_coefficient", 1e-3}}}), "ViscousDamping on a rod");
  json mass_with_spans = straightRod(5);
  mass_with_spans.erase("density");
  mass_with_spans["mass"] = 1e-3;
  mass_with_spans["spans"] = {{{"from", 0.0}, {"to", 0.5}, {"radius", 5e-4}}};
  refused(mass_with_spans, base, json::array(), "density");
  // A lumen that leaves no wall, on the body or under a span's thinner radius.
  json no_wall = straightRod(5);
  no_wall["inner_radius"] = no_wall["radius"];
  refused(no_wall, base, json::array(), "/inner_radius");
  json thin_span = straightRod(5);
  thin_span["inner_radius"] = 0.5 * thin_span["radius"].get<double>();
  thin_span["spans"] = {{{"from", 0.5}, {"to", 1.0}, {"radius", 0.4 * thin_span["radius"].get<double>()}}};
  refused(thin_span, base, json::array(), "/spans/0/radius");
  thin_span["spans"][0]["inner_radius"] = thin_span["spans"][0]["radius"];
  refused(thin_span, base, json::array(), "/spans/0/inner_radius");
}

}  // namespace
}  // namespace filum
