// FramedChain + ChainElasticity (framed_chain.hpp, chain_elasticity.hpp): a chain of point masses
// with a frame per segment, the second body kind, against physics.
//
// Material: a soft polymer rod (E = 1 MPa, ν = 0.5, ρ = 1000 kg/m³, r = 1 mm); segments of 1 cm.
// Its shear modes are the stiffest (ω ~ √(4κG/ρ) / r ≈ 3.5e4 rad/s: thin frames have little
// rotary inertia); RK4 steps of 1e-7 to 4e-7 s keep ω dt <= 1.4e-2, deep in the asymptotic range.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <tuple>

#include "filum/all_components.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/geometry/rotation_vector.hpp"
#include "filum/mechanics/chain_elasticity.hpp"
#include "filum/mechanics/framed_chain.hpp"
#include "support/finite_difference.hpp"

namespace filum {
namespace {

using nlohmann::json;
using mechanics::ChainElasticity;
using mechanics::FramedChain;

json chainScene(int nodes, double dt, double duration, const std::string& integrator = "RungeKutta4",
                json angular_velocities = nullptr) {
  json chain = {{"type", "FramedChain"},
                {"nodes", {{"from", {0, 0, 0}}, {"to", {0.01 * (nodes - 1), 0, 0}}, {"count", nodes}}},
                {"radius", 1e-3},
                {"density", 1000.0}};
  if (!angular_velocities.is_null()) chain["angular_velocities"] = angular_velocities;
  return {{"dt", dt},
          {"duration", duration},
          {"gravity", {0, 0, 0}},
          {"integrator", {{"type", integrator}}},
          {"nodes",
           {{{"name", "rod"},
             {"components", {chain, {{"type", "ChainElasticity"}, {"youngs_modulus", 1e6}, {"poisson_ratio", 0.5}}}}}}}};
}

std::unique_ptr<Scene> load(const json& document) {
  auto scene = loadScene(document, "framed chain test", app::makeFactory());
  scene->init();
  return scene;
}

const FramedChain& chainOf(const Scene& scene) { return dynamic_cast<const FramedChain&>(*scene.bodies().front()); }
const ChainElasticity& elasticityOf(const Scene& scene) {
  return dynamic_cast<const ChainElasticity&>(*scene.forceFields().front());
}

/// A state moved off the straight rest: points by up to 0.5 mm, frames turned by up to 0.1 rad
/// (through the body's own q ⊕ w), random velocities and angular velocities.
SceneState perturbed(const Scene& scene, unsigned seed, double speed) {
  SceneState s = scene.state();
  std::srand(seed);
  VecX w = 0.1 * VecX::Random(scene.velocitySize());
  w.head(3 * scene.dofPointCount()) *= 5e-3;  // 0.5 mm on the points
  scene.integratePositions(s.q, w, 1.0, s.q);
  s.v = speed * VecX::Random(scene.velocitySize());
  return s;
}

TEST(FramedChain, ForcesAndTorquesAreMinusTheEnergyGradient) {
  // Points: Q = −∂E/∂x by central differences; frames: τ = −dE/dδ for R ← R exp(δ), also central.
  // Step h = 1e-7 (m, rad): truncation (h/L)²/6 ≈ 2e-11 relative for the 1 cm segments (and
  // h²/6 for angles); round-off ε |E| / h ≈ 2e-16 · 2e-4 J / 1e-7 ≈ 4e-13, in N and in N·m.
  // Forces (N) and torques (N·m) are checked each against their own largest entry, 1e-6
  // relative: the bending and twist torques (~1e-5 N·m) are then checked to ~1e-11 N·m, so the
  // SO(3) Jacobians (J_r⁻¹, J_l⁻¹ change a torque by |φ × Bφ|/l ≈ 2e-7 N·m here) are seen.
  auto scene = load(chainScene(5, 1e-7, 1e-6));
  const ChainElasticity& field = elasticityOf(*scene);
  const SceneState s = perturbed(*scene, 3, 0.0);
  VecX Q = VecX::Zero(scene->velocitySize());
  field.addForce(s, Q);
  VecX fd(scene->velocitySize());
  const double h = 1e-7;
  for (int j = 0; j < scene->velocitySize(); ++j) {
    VecX w = VecX::Zero(scene->velocitySize());
    w[j] = h;
    SceneState plus = s, minus = s;
    scene->integratePositions(s.q, w, 1.0, plus.q);
    scene->integratePositions(s.q, w, -1.0, minus.q);
    fd[j] = -(field.potentialEnergy(plus) - field.potentialEnergy(minus)) / (2.0 * h);
  }
  const Eigen::Index points = 3 * scene->dofPointCount(), frames = scene->velocitySize() - points;
  for (const auto& [first, count, what] : {std::tuple<Eigen::Index, Eigen::Index, const char*>{0, points, "forces"},
                                          {points, frames, "torques"}}) {
    const double scale = fd.segment(first, count).cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 0.0) << what;
    EXPECT_LE((Q - fd).segment(first, count).cwiseAbs().maxCoeff(), 1e-6 * scale)
        << what << ": analytic " << Q.segment(first, count).transpose() << "\nFD " << fd.segment(first, count).transpose();
  }
}

TEST(FramedChain, TwistOscillatesAtTheTorsionalFrequency) {
  // Two segments' frames twisted against each other (ω = ∓w about d3): only the twist term at the
  // node between them acts (d3 and the edges stay put, ω ∥ e3 makes no gyroscopic torque), so the
  // relative twist ψ obeys, with the node's Voronoi length ℓ = l,
  //   J3 ψ̈ = −2 G J ψ / ℓ,  ψ(0) = 0, ψ̇(0) = 2w  ⇒  ψ(t) = (2w/Ω) sin Ω t,  Ω = √(2 G J / (ℓ J3)).
  // RK4 at Ω dt ≈ 1e-3: relative error ~ (Ω dt)⁴ Ω T / 120; 1e-9 asserted.
  const double w = 2.0;
  auto probe = load(chainScene(3, 1e-7, 1e-7));
  const FramedChain& chain0 = chainOf(*probe);
  const double l = chain0.restLength(0), J3 = chain0.segmentInertia(0).z();
  const double Omega = std::sqrt(2.0 * elasticityOf(*probe).bendingTwistingStiffness(0).z() / (l * J3));
  const double T = 1.2 / Omega, dt = T / 1200.0;
  auto scene = load(chainScene(3, dt, T, "RungeKutta4", {{0, 0, -w}, {0, 0, w}}));
  for (int k = 0; k < 1200; ++k) ASSERT_TRUE(scene->step().ok);
  const FramedChain& chain = chainOf(*scene);
  const Vec3 phi = geometry::rotationLog(chain.orientation(scene->state().q, 0).conjugate() *
                                         chain.orientation(scene->state().q, 1));
  const double exact = 2.0 * w / Omega * std::sin(Omega * scene->state().time);
  std::cout << "  Ω = " << Omega << " rad/s, ψ(T) = " << phi.z() << ", exact " << exact << '\n';
  EXPECT_NEAR(phi.z(), exact, 1e-9 * std::abs(exact));
  EXPECT_LE(phi.head<2>().norm(), 1e-12 * std::abs(exact));  // no bending appears
}

struct Invariants {
  double energy;
  Vec3 momentum, angular_momentum;
};

Invariants invariants(const Scene& scene) {
  const FramedChain& chain = chainOf(scene);
  const SceneState& s = scene.state();
  Invariants out{scene.energy(s).total(), Vec3::Zero(), Vec3::Zero()};
  const ConstPointsMap x = chain.block(s.q), v = chain.block(s.v);
  const auto omega = chain.internalVelocities(s.v);
  for (int i = 0; i < chain.pointCount(); ++i) {
    const Vec3 p = chain.nodeMass(i) * v.row(i).transpose();
    out.momentum += p;
    out.angular_momentum += x.row(i).transpose().cross(p);
  }
  for (int i = 0; i < chain.segmentCount(); ++i)  // L += R J ω (each frame's spin, turned to the world)
    out.angular_momentum += chain.orientation(s.q, i) * chain.segmentInertia(i).cwiseProduct(omega.segment<3>(3 * i));
  return out;
}

TEST(FramedChain, AFreeChainConservesEnergyAndMomentaAtTheSchemesOrder) {
  // A free 5-node chain, bent, twisted and moving: E, P and L are invariants of its dynamics
  // (the energy is invariant under rigid motions). P is conserved by every scheme (forces come in
  // opposite pairs): to round-off. E and L drift by RK4's error, second order here (the frames'
  // update matches the first Magnus term only, and the forces depend on the frames): halving dt
  // divides the drift by 4 to 16 — at least 3.5 and at most 20 is asserted (a quarter of the
  // next order's share either way at ω dt <= 1.4e-2, the shear modes' ω ≈ 3.5e4 rad/s); more
  // than 16 would mean the drift is round-off, not the scheme's. The steps are large enough that
  // the drift (~1e-10) stands well above the energy's round-off over the run (~1e-12, which
  // 2e-8 and 1e-8 s steps reached once the frames sat on the segments).
  const auto drift = [](double dt) {
    auto scene = load(chainScene(5, dt, 2e-4));
    scene->setState(perturbed(*scene, 7, 0.05));
    const Invariants start = invariants(*scene);
    const long steps = std::lround(2e-4 / dt);
    for (long k = 0; k < steps; ++k) EXPECT_TRUE(scene->step().ok);
    const Invariants end = invariants(*scene);
    return std::array<double, 3>{std::abs(end.energy - start.energy) / std::abs(start.energy),
                                 (end.momentum - start.momentum).norm() / start.momentum.norm(),
                                 (end.angular_momentum - start.angular_momentum).norm() / start.angular_momentum.norm()};
  };
  const auto coarse = drift(4e-7), fine = drift(2e-7);
  std::cout << "  energy drift " << coarse[0] << " -> " << fine[0] << ", momentum " << coarse[1] << " -> " << fine[1]
            << ", angular momentum " << coarse[2] << " -> " << fine[2] << '\n';
  EXPECT_LE(fine[1], 1e-12);  // round-off of 1e3 steps of pairwise-cancelling forces
  EXPECT_GE(coarse[0] / fine[0], 3.5);
  EXPECT_LE(coarse[0] / fine[0], 20.0);
  EXPECT_GE(coarse[2] / fine[2], 3.5);
  EXPECT_LE(coarse[2] / fine[2], 20.0);
}

TEST(FramedChain, FrameDifferencesInvertFrameIncrements) {
  // differenceInternal(q0 ⊕ w, q0) = w for turns below π (log ∘ exp): to the round-off of a
  // quaternion product and atan2 on angles up to 3 rad, ~1e-15 rad; 1e-14 asserted.
  auto scene = load(chainScene(4, 1e-7, 1e-6));
  const FramedChain& chain = chainOf(*scene);
  const SceneState s = perturbed(*scene, 11, 0.0);
  std::srand(5);
  VecX w = 2.0 * VecX::Random(chain.internalVelocityCount());
  for (int i = 0; i < chain.segmentCount(); ++i)  // turns of at most 3 rad (< π: log is unique)
    if (w.segment<3>(3 * i).norm() > 3.0) w.segment<3>(3 * i) *= 3.0 / w.segment<3>(3 * i).norm();
  VecX q1(chain.internalPositionCount()), back(chain.internalVelocityCount());
  chain.integrateInternal(chain.internalPositions(s.q), w, q1);
  chain.differenceInternal(q1, chain.internalPositions(s.q), back);
  EXPECT_LE((back - w).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(FramedChain, RefusesPointChanges) {
  auto scene = load(chainScene(3, 1e-7, 1e-6));
  auto& chain = dynamic_cast<FramedChain&>(*scene->bodies().front());
  EXPECT_THROW(scene->refine(chain, {0.5}), SceneError);
  EXPECT_THROW(scene->cut(chain, 0.5), SceneError);
}

TEST(FramedChain, ASectionsRadiusIsItsSegmentsAndTheLargerAtANodeBetweenTwo) {
  // Uneven segments (0.3, 0.2, 0.5 m): nodes at s = 0.3 and 0.5. Segment radii 1, 3 and 2 mm.
  Points nodes(4, 3);
  nodes << 0, 0, 0, 0.3, 0, 0, 0.5, 0, 0, 1.0, 0, 0;
  const FramedChain chain(nodes, 1e-3, {{1e-3, 1000.0}, {3e-3, 1000.0}, {2e-3, 1000.0}});
  EXPECT_TRUE(chain.radiusVaries());
  EXPECT_EQ(chain.radiusAt(0.0), 1e-3);
  EXPECT_EQ(chain.radiusAt(0.2), 1e-3);
  EXPECT_EQ(chain.radiusAt(0.4), 3e-3);
  EXPECT_EQ(chain.radiusAt(0.7), 2e-3);
  EXPECT_EQ(chain.radiusAt(1.0), 2e-3);
  // At a node, and a few ulps either side of it (an abscissa summed another way, as a contact
  // sphere's from its arc-length table): the larger of the two segments'.
  for (const double node : {0.3, 0.5})
    for (const double s : {node, std::nextafter(node, 0.0), std::nextafter(node, 1.0)}) EXPECT_EQ(chain.radiusAt(s), 3e-3) << s;
  const FramedChain uniform(nodes, 1e-3, {{1e-3, 1000.0}, {1e-3, 1000.0}, {1e-3, 1000.0}});
  EXPECT_FALSE(uniform.radiusVaries());
  EXPECT_EQ(uniform.radiusAt(0.3), 1e-3);
}

}  // namespace
}  // namespace filum
