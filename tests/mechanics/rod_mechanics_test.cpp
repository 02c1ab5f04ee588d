// The rod (FramedChain + ChainElasticity + RodEndFrame, with PointLoad and gravity) against the
// mechanics of rods, with references computed here from the equations: the small-deflection
// cantilever, the large-deflection elastica under a tip load and under its own weight (shooting
// solutions of Kirchhoff's equations, support/elastica_shooting.hpp), torsion and the first
// bending frequency.
//
// Statics: the equilibrium of the discrete rod is found by Newton's method on its generalized
// forces, node 0 held (support/rod_statics.hpp); RodEndFrame holds the frame at the clamp.
//
// Material, real: a polymer catheter-like rod, r = 1 mm, L = 0.2 m, ρ = 1100 kg/m³, ν = 0.5, with
// E set from the load parameter Γ = ρ A g L³ / (E I) of the two rods asked for (Γ = 5:
// E ≈ 69 MPa, polyurethane; Γ = 20: 17 MPa, silicone).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "filum/all_components.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/geometry/rotation_vector.hpp"
#include "filum/mechanics/chain_elasticity.hpp"
#include "filum/mechanics/framed_chain.hpp"
#include "support/elastica_shooting.hpp"
#include "support/rod_statics.hpp"

namespace filum {
namespace {

using nlohmann::json;
using mechanics::FramedChain;
using test::equilibrium;
using test::rodForces;

using namespace test::rod;  // kLength, kRadius, kDensity, kGravity, kArea, kSecond, modulusFor

/// The rod's stiffnesses for the reference: EI, E A and κ G A with κ = 0.9 and G = E/3 (ν = ½:
/// Cowper's κ of a disc, 6(1 + ν)/(7 + 6ν), as ChainElasticity takes it).
test::RodStiffness stiffnessOf(double E) { return {E * kSecond, E * kArea, 0.9 * E / 3.0 * kArea}; }


struct RodCase {
  int nodes = 21;
  double youngs_modulus = 1e7;  // Pa
  bool weight = false;          // gravity (0, 0, −g)
  Vec3 tip_force = Vec3::Zero();   // N, at s = 1
  Vec3 tip_torque = Vec3::Zero();  // N·m, at s = 1
  double inner_radius = 0.0;       // m: a tube's lumen (0: the solid rod)
};

std::unique_ptr<Scene> rodScene(const RodCase& c) {
  json chain = {{"type", "FramedChain"},
                {"nodes", {{"from", {0, 0, 0}}, {"to", {kLength, 0, 0}}, {"count", c.nodes}}},
                {"radius", kRadius},
                {"density", kDensity}};
  if (c.inner_radius > 0.0) chain["inner_radius"] = c.inner_radius;
  json components = {chain,
                     {{"type", "ChainElasticity"}, {"youngs_modulus", c.youngs_modulus}, {"poisson_ratio", 0.5}},
                     {{"type", "RodEndFrame"}, {"end", "start"}}};
  if (c.tip_force != Vec3::Zero() || c.tip_torque != Vec3::Zero())
    components.push_back({{"type", "PointLoad"},
                          {"abscissa", 1.0},
                          {"force", {c.tip_force.x(), c.tip_force.y(), c.tip_force.z()}},
                          {"torque", {c.tip_torque.x(), c.tip_torque.y(), c.tip_torque.z()}}});
  const json document = {{"dt", 1e-6},
                         {"duration", 1e-6},
                         {"gravity", {0, 0, c.weight ? -kGravity : 0.0}},
                         {"integrator", {{"type", "RungeKutta4"}}},
                         {"nodes", {{{"name", "rod"}, {"components", components}}}}};
  auto scene = loadScene(document, "rod mechanics test", app::makeFactory());
  scene->init();
  return scene;
}

Vec3 tipOf(const Scene& scene, const SceneState& s) {
  const auto& chain = dynamic_cast<const FramedChain&>(*scene.bodies().front());
  return chain.block(s.q).row(chain.pointCount() - 1).transpose();
}

/// |tip − exact| over the exact deflection |exact − (L, 0, 0)|.
double tipError(const RodCase& c, const test::ElasticaTip& exact) {
  auto scene = rodScene(c);
  const SceneState s = equilibrium(*scene, 20);
  const Vec3 tip = tipOf(*scene, s), reference(exact.x, 0.0, exact.z);
  return (tip - reference).norm() / (reference - Vec3(kLength, 0, 0)).norm();
}

TEST(RodMechanics, ShootingReferenceMatchesTheSmallDeflectionCantilever) {
  // The reference itself: small loads give Euler–Bernoulli's tip deflections, P L³ / (3 E I) and
  // w L⁴ / (8 E I), to the geometric nonlinearity, O((δ/L)²) ≈ 1e-10 relative at δ/L = 1e-5.
  const double E = 1e7, EI = E * kSecond, P = 1e-5 * 3.0 * EI / std::pow(kLength, 2), w = 1e-5 * 8.0 * EI / std::pow(kLength, 3);
  EXPECT_NEAR(-test::elasticaTip(kLength, {EI}, 0.0, P).z, P * std::pow(kLength, 3) / (3.0 * EI), 1e-8 * 1e-5 * kLength);
  EXPECT_NEAR(-test::elasticaTip(kLength, {EI}, w, 0.0).z, w * std::pow(kLength, 4) / (8.0 * EI), 1e-8 * 1e-5 * kLength);
  // With shear: Timoshenko's tip deflection P L³ / (3 E I) + P L / (κ G A).
  const test::RodStiffness rod = stiffnessOf(E);
  EXPECT_NEAR(-test::elasticaTip(kLength, rod, 0.0, P).z, P * std::pow(kLength, 3) / (3.0 * EI) + P * kLength / rod.shear,
              1e-8 * 1e-5 * kLength);
}

TEST(RodMechanics, CantileverWithEndLoadDeflectsByPL3Over3EI) {
  // δ/L = 1e-4: geometric nonlinearity ~1e-8 relative. Timoshenko's deflection (the rod
  // shears: + P L / κGA, 2.8e-5 relative). The discretization error is second order in the
  // segment length: e(21) <= 1 % and each halving of the segments divides it by 4 (an observed
  // order within 0.25 of 2; the next term of the error, O(l³), shifts the ratio by O(l/L)).
  const double E = 1e7, EI = E * kSecond, P = 1e-4 * 3.0 * EI / (kLength * kLength);
  const double exact = P * std::pow(kLength, 3) / (3.0 * EI) + P * kLength / stiffnessOf(E).shear;
  std::vector<double> errors;
  for (const int nodes : {11, 21, 41}) {
    RodCase c{nodes, E, false, Vec3(0, 0, -P)};
    auto scene = rodScene(c);
    const SceneState s = equilibrium(*scene, 1);
    errors.push_back(std::abs(-tipOf(*scene, s).z() - exact) / exact);
    std::cout << "  " << nodes << " nodes: tip deflection error " << errors.back() << '\n';
  }
  EXPECT_LE(errors[1], 1e-2);
  const double order = std::log2(errors[1] / errors[2]);
  EXPECT_NEAR(order, 2.0, 0.25);
}

TEST(RodMechanics, EndLoadedElasticaMatchesTheShootingSolution) {
  // P L² / (E I) = 3: the tip turns by about 60°. The reference is Reissner's rod with the
  // discrete rod's E A and κ G A (they move the tip by ~1e-4 of the deflection, which would
  // otherwise hide the discretization error at 81 nodes). To 1 % at 21 nodes, second order as
  // the segments halve (as above).
  const double E = 1e7, EI = E * kSecond, P = 3.0 * EI / (kLength * kLength);
  const test::ElasticaTip exact = test::elasticaTip(kLength, stiffnessOf(E), 0.0, P);
  std::vector<double> errors;
  for (const int nodes : {21, 41, 81}) {
    errors.push_back(tipError({nodes, E, false, Vec3(0, 0, -P)}, exact));
    std::cout << "  " << nodes << " nodes: tip error " << errors.back() << " of the deflection\n";
  }
  EXPECT_LE(errors[0], 1e-2);
  EXPECT_NEAR(std::log2(errors[1] / errors[2]), 2.0, 0.25);
}

TEST(RodMechanics, SelfWeightElasticaMatchesTheShootingSolution) {
  // The two rods asked for: Γ = 5 (tip drop 0.496 L) and Γ = 20 (0.830 L) by the elastica. To 1 % at
  // 21 nodes, second order as the segments halve.
  for (const double gamma : {5.0, 20.0}) {
    const double E = modulusFor(gamma), w = kDensity * kArea * kGravity;
    const test::ElasticaTip exact = test::elasticaTip(kLength, stiffnessOf(E), w, 0.0);
    std::vector<double> errors;
    for (const int nodes : {21, 41, 81}) {
      errors.push_back(tipError({nodes, E, true}, exact));
      std::cout << "  Γ = " << gamma << ", " << nodes << " nodes: tip drop " << -exact.z / kLength
                << " L exact, error " << errors.back() << " of the deflection\n";
    }
    EXPECT_LE(errors[0], 1e-2) << "Γ = " << gamma;
    EXPECT_NEAR(std::log2(errors[1] / errors[2]), 2.0, 0.25) << "Γ = " << gamma;
  }
}

TEST(RodMechanics, EndTorqueTwistsByTLOverGJ) {
  // A torque T about the rod's axis at the free end: the twist grows linearly from the clamp,
  // ψ(s) = T s / (G J). The last frame sits at the centre of the last segment, s = L − l/2, and
  // the discrete rod's twist joints (RodEndFrame's half segment, then whole segments) add up to
  // exactly that length, so ψ matches to the solve's round-off (1e-10 relative asserted; a twist
  // about one fixed axis composes exactly in log(R_iᵀ R_j)).
  const double E = 1e7, G = E / 3.0, GJ = G * 2.0 * kSecond, T = 0.5 * GJ / kLength;  // ψ(L) = 0.5 rad
  const int nodes = 21;
  auto scene = rodScene({nodes, E, false, Vec3::Zero(), Vec3(T, 0, 0)});
  const SceneState s = equilibrium(*scene, 1);
  const auto& chain = dynamic_cast<const FramedChain&>(*scene->bodies().front());
  const Vec3 turn = geometry::rotationLog(chain.initialFrame(nodes - 2).conjugate() * chain.orientation(s.q, nodes - 2));
  const double l = kLength / (nodes - 1), exact = T * (kLength - l / 2.0) / GJ;
  EXPECT_NEAR(turn.z(), exact, 1e-10 * exact);   // about the frame's own d3
  EXPECT_LE(turn.head<2>().norm(), 1e-10 * exact);  // and nothing else
}

TEST(RodMechanics, TwistStaysPutWhenTheTwistedRodBends) {
  // A straight rod twisted by an end torque T (ψ = T (L − l/2) / GJ at the last frame), then bent
  // by a transverse tip force as well (tip slope θ ≈ 1.5e-3): bending and twist of an isotropic
  // rod, straight at rest, are uncoupled to first order, so the total twist — the twist
  // components of the relative turns from the held frame to the last, Σ φ_z — stays ψ up to
  // O(θ²) ≈ 2e-6 relative (1e-5 asserted).
  const double E = 1e7, G = E / 3.0, GJ = G * 2.0 * kSecond, EI = E * kSecond, T = 0.5 * GJ / kLength;
  const double P = 1e-3 * 2.0 * EI / (kLength * kLength);  // tip slope P L² / (2 E I) = 1e-3
  const int nodes = 21;
  auto scene = rodScene({nodes, E, false, Vec3(0, -P, 0), Vec3(T, 0, 0)});
  const SceneState s = equilibrium(*scene, 4);
  const auto& chain = dynamic_cast<const FramedChain&>(*scene->bodies().front());
  double twist = geometry::rotationLog(chain.initialFrame(0).conjugate() * chain.orientation(s.q, 0)).z();
  for (int j = 1; j < chain.segmentCount(); ++j)
    twist += geometry::rotationLog(chain.orientation(s.q, j - 1).conjugate() * chain.orientation(s.q, j)).z();
  const double l = kLength / (nodes - 1), exact = T * (kLength - l / 2.0) / GJ;
  const Vec3 tip = chain.block(s.q).row(nodes - 1).transpose();
  std::cout << "  twist " << twist << " rad, straight " << exact << ", tip deflection " << -tip.y() << " m\n";
  EXPECT_GT(-tip.y(), 0.5 * P * std::pow(kLength, 3) / (3.0 * EI));  // it did bend
  EXPECT_NEAR(twist, exact, 1e-5 * exact);
}

/// The discrete rod's lowest angular frequency about its rest state, held at node 0 (its three
/// coordinates removed), from the generalized eigenproblem K u = ω² M u (K = −∂F/∂w by central
/// differences, M the lumped masses and the frames' inertia).
double lowestFrequency(Scene& scene) {
  const SceneState s = scene.state();
  const int n = scene.velocitySize(), free = n - 3;
  MatX K(free, free);
  const double h = 1e-8;
  for (int k = 0; k < free; ++k) {
    VecX w = VecX::Zero(n);
    w[3 + k] = 1.0;
    SceneState plus = s, minus = s;
    scene.integratePositions(s.q, w, h, plus.q);
    scene.integratePositions(s.q, w, -h, minus.q);
    K.col(k) = -(rodForces(scene, plus, 1.0) - rodForces(scene, minus, 1.0)).tail(free) / (2.0 * h);
  }
  K = 0.5 * (K + K.transpose()).eval();  // symmetric to the differences' round-off
  const auto& chain = dynamic_cast<const FramedChain&>(*scene.bodies().front());
  VecX mass(n);
  for (int i = 0; i < chain.pointCount(); ++i) mass.segment<3>(3 * i).setConstant(chain.nodeMass(i));
  for (int i = 0; i < chain.segmentCount(); ++i)
    mass.segment<3>(3 * chain.pointCount() + 3 * i) = chain.segmentInertia(i);
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatX> modes(K, MatX(mass.tail(free).asDiagonal()));
  EXPECT_EQ(modes.info(), Eigen::Success);
  return std::sqrt(modes.eigenvalues()[0]);
}

TEST(RodMechanics, FirstBendingFrequencyIsEulerBernoullis) {
  // ω₁ = 1.8751² √(E I / (ρ A L⁴)) for the clamped-free beam. Rotary inertia and shear lower ω₁
  // by O((r/L)²) ≈ 1e-4; the discretization error is second order: within 1 % at 21 nodes.
  const double E = 1e7;
  auto scene = rodScene({21, E});
  const double omega = lowestFrequency(*scene);
  const double exact = std::pow(1.8751040687, 2) * std::sqrt(E * kSecond / (kDensity * kArea * std::pow(kLength, 4)));
  std::cout << "  ω₁ = " << omega << " rad/s, Euler–Bernoulli " << exact << '\n';
  EXPECT_NEAR(omega, exact, 1e-2 * exact);
}

// A tube: the same rod with a lumen of 0.7 mm, a catheter's wall of 0.3 mm. Its wall alone carries
// mass and stiffness: A = π (R² − r²), I = π (R⁴ − r⁴)/4, J = 2I — a solid section of the same
// radius would be 1/(1 − 0.7⁴) = 1.32 times stiffer in bending, and 2.0 times heavier.
constexpr double kInner = 7e-4;
constexpr double kTubeArea = std::numbers::pi * (kRadius * kRadius - kInner * kInner);
constexpr double kTubeSecond =
    std::numbers::pi * (kRadius * kRadius * kRadius * kRadius - kInner * kInner * kInner * kInner) / 4.0;

/// Timoshenko's shear coefficient of a hollow circle (Cowper, J. Appl. Mech. 33 (1966) 335,
/// Table 1), m = r/R: 6 (1 + ν)(1 + m²)² / ((7 + 6ν)(1 + m²)² + (20 + 12ν) m²).
double cowperTube(double nu, double m) {
  const double a = std::pow(1.0 + m * m, 2);
  return 6.0 * (1.0 + nu) * a / ((7.0 + 6.0 * nu) * a + (20.0 + 12.0 * nu) * m * m);
}

TEST(RodMechanics, ATubesMassAndRotaryInertiaAreItsWallsAlone) {
  // m = ρ A L and each segment's J = ρ l diag(I, I, 2I), to the sums' round-off (1e-14 relative).
  auto scene = rodScene({21, 1e7, false, Vec3::Zero(), Vec3::Zero(), kInner});
  const auto& chain = dynamic_cast<const FramedChain&>(*scene->bodies().front());
  EXPECT_NEAR(chain.mass(), kDensity * kTubeArea * kLength, 1e-14 * chain.mass());
  const double l = kLength / 20.0;
  const Vec3 inertia = kDensity * l * Vec3(kTubeSecond, kTubeSecond, 2.0 * kTubeSecond);
  EXPECT_LE((chain.segmentInertia(7) - inertia).norm(), 1e-14 * inertia.norm());
  // Given by its total mass instead, the tube takes the density that mass gives its wall.
  const json document = {{"dt", 1e-3}, {"duration", 1e-3},
                         {"nodes", {{{"name", "rod"}, {"components", {{{"type", "FramedChain"},
                                                                        {"nodes", {{"from", {0, 0, 0}}, {"to", {kLength, 0, 0}}, {"count", 21}}},
                                                                        {"radius", kRadius},
                                                                        {"inner_radius", kInner},
                                                                        {"mass", chain.mass()}}}}}}}};
  auto by_mass = loadScene(document, "tube by mass", app::makeFactory());
  const auto& same = dynamic_cast<const FramedChain&>(*by_mass->bodies().front());
  EXPECT_NEAR(same.segmentSection(3).density, kDensity, 1e-14 * kDensity);
  EXPECT_LE((same.segmentInertia(7) - inertia).norm(), 1e-14 * inertia.norm());
}

TEST(RodMechanics, ATubeCantileverDeflectsByItsWallsSecondMoment) {
  // As the solid cantilever above, with the wall's I, A and Cowper's κ of a tube (m = 0.7): the
  // deflection P L³/(3 E I) + P L/(κ G A) to 1 % at 21 nodes and second order as the segments
  // halve. A solid section's I would be off by 32 %.
  const double E = 1e7, EI = E * kTubeSecond, P = 1e-4 * 3.0 * EI / (kLength * kLength);
  const double kGA = cowperTube(0.5, kInner / kRadius) * E / 3.0 * kTubeArea;
  const double exact = P * std::pow(kLength, 3) / (3.0 * EI) + P * kLength / kGA;
  std::vector<double> errors;
  for (const int nodes : {11, 21, 41}) {
    auto scene = rodScene({nodes, E, false, Vec3(0, 0, -P), Vec3::Zero(), kInner});
    const SceneState s = equilibrium(*scene, 1);
    errors.push_back(std::abs(-tipOf(*scene, s).z() - exact) / exact);
    std::cout << "  " << nodes << " nodes: tip deflection error " << errors.back() << '\n';
  }
  EXPECT_LE(errors[1], 1e-2);
  EXPECT_NEAR(std::log2(errors[1] / errors[2]), 2.0, 0.25);
}

TEST(RodMechanics, ATubeTwistsByItsWallsPolarMoment) {
  // ψ = T (L − l/2) / (G J) at the last frame, J = 2 I of the wall, to the solve's round-off as
  // for the solid rod (EndTorqueTwistsByTLOverGJ).
  const double E = 1e7, GJ = E / 3.0 * 2.0 * kTubeSecond, T = 0.5 * GJ / kLength;
  const int nodes = 21;
  auto scene = rodScene({nodes, E, false, Vec3::Zero(), Vec3(T, 0, 0), kInner});
  const SceneState s = equilibrium(*scene, 1);
  const auto& chain = dynamic_cast<const FramedChain&>(*scene->bodies().front());
  const Vec3 turn = geometry::rotationLog(chain.initialFrame(nodes - 2).conjugate() * chain.orientation(s.q, nodes - 2));
  const double l = kLength / (nodes - 1), exact = T * (kLength - l / 2.0) / GJ;
  EXPECT_NEAR(turn.z(), exact, 1e-10 * exact);
  EXPECT_LE(turn.head<2>().norm(), 1e-10 * exact);  // and nothing else
}

TEST(RodMechanics, AShortTubeShearsByCowpersCoefficient) {
  // A stub of tube, L = 5 mm of the 1 mm tube with a 0.7 mm lumen, ν = 0.3: shear is a sixth of
  // its tip deflection, P L/(κGA) beside P L³/(3EI), so the shear coefficient shows. Cowper's κ
  // for m = 0.7 and ν = 0.3 is 0.557 (the reference's formula checked below against its limits:
  // 0.886 for a disc, Cowper's 2(1 + ν)/(4 + 3ν) for a thin wall); the disc's 0.9 would move
  // the tip by 6.6 %. Timoshenko's deflection to 1 % at 21 nodes, second order as the segments
  // halve (as the long cantilever).
  EXPECT_NEAR(cowperTube(0.3, 0.0), 6.0 * 1.3 / 8.8, 1e-15);
  EXPECT_NEAR(cowperTube(0.3, 1.0 - 1e-9), 2.0 * 1.3 / 4.9, 1e-8);
  const double L = 5e-3, E = 1e7, G = E / 2.6, EI = E * kTubeSecond;
  const double P = 1e-4 * 3.0 * EI / (L * L);
  const double bending = P * L * L * L / (3.0 * EI), shear = P * L / (cowperTube(0.3, kInner / kRadius) * G * kTubeArea);
  const double exact = bending + shear;
  std::vector<double> errors;
  for (const int nodes : {11, 21, 41}) {
    const json document = {
        {"dt", 1e-6}, {"duration", 1e-6}, {"gravity", {0, 0, 0}}, {"integrator", {{"type", "RungeKutta4"}}},
        {"nodes", {{{"name", "stub"}, {"components", {{{"type", "FramedChain"},
                                                        {"nodes", {{"from", {0, 0, 0}}, {"to", {L, 0, 0}}, {"count", nodes}}},
                                                        {"radius", kRadius}, {"inner_radius", kInner}, {"density", kDensity}},
                                                       {{"type", "ChainElasticity"}, {"youngs_modulus", E}, {"poisson_ratio", 0.3}},
                                                       {{"type", "RodEndFrame"}, {"end", "start"}},
                                                       {{"type", "PointLoad"}, {"abscissa", 1.0}, {"force", {0, 0, -P}}}}}}}}};
    auto scene = loadScene(document, "tube stub", app::makeFactory());
    scene->init();
    const SceneState s = equilibrium(*scene, 1);
    errors.push_back(std::abs(-tipOf(*scene, s).z() - exact) / exact);
    std::cout << "  " << nodes << " nodes: tip deflection error " << errors.back() << " (shear " << shear / exact
              << " of it)\n";
  }
  EXPECT_LE(errors[1], 1e-2);
  EXPECT_NEAR(std::log2(errors[1] / errors[2]), 2.0, 0.25);
}

TEST(RodMechanics, ATubesFirstBendingFrequencyIsEulerBernoullis) {
  // ω₁ = 1.8751² √(E I / (ρ A L⁴)) with the wall's I and A: I/A = (R² + r²)/4 is larger than a
  // disc's, so rotary inertia and shear lower ω₁ by O((E/κG)(R² + r²)/L²) ≈ 1e-4; within 1 % at
  // 21 nodes as for the solid rod. (The solid section's ω₁ is √(R²/(R² + r²)) = 0.82 times the
  // tube's.)
  const double E = 1e7;
  auto scene = rodScene({21, E, false, Vec3::Zero(), Vec3::Zero(), kInner});
  const double omega = lowestFrequency(*scene);
  const double exact = std::pow(1.8751040687, 2) * std::sqrt(E * kTubeSecond / (kDensity * kTubeArea * std::pow(kLength, 4)));
  std::cout << "  ω₁ = " << omega << " rad/s, Euler–Bernoulli " << exact << '\n';
  EXPECT_NEAR(omega, exact, 1e-2 * exact);
}

}  // namespace
}  // namespace filum
