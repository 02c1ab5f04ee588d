// Implicit steps for rods (FramedChain + ChainElasticity + RodEndFrame under ImplicitEuler): the
// analytic Jacobian against finite differences, the step against the static equilibrium it must
// settle on, and the invariants of backward Euler (momentum kept, energy not created).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "filum/all_components.hpp"
#include "filum/core/jacobian_accumulator.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/mechanics/framed_chain.hpp"
#include "filum/mechanics/step_matrix.hpp"
#include "support/rod_statics.hpp"

namespace filum {
namespace {

using nlohmann::json;
using mechanics::FramedChain;

using namespace test::rod;  // kLength, kRadius, kDensity, kArea, kSecond, modulusFor

json rodDocument(int nodes, double youngs_modulus, double gravity, const json& integrator, const json& more, double dt,
                 double duration) {
  json components = {{{"type", "FramedChain"},
                      {"nodes", {{"from", {0, 0, 0}}, {"to", {kLength, 0, 0}}, {"count", nodes}}},
                      {"radius", kRadius},
                      {"density", kDensity}},
                     {{"type", "ChainElasticity"}, {"youngs_modulus", youngs_modulus}, {"poisson_ratio", 0.5}}};
  for (const json& c : more) components.push_back(c);
  return {{"dt", dt},
          {"duration", duration},
          {"gravity", {0, 0, -gravity}},
          {"integrator", integrator},
          {"constraint_solver", {{"type", "LagrangeMultiplierSolver"}}},
          {"nodes", {{{"name", "rod"}, {"components", components}}}}};
}

std::unique_ptr<Scene> load(const json& document) {
  auto scene = loadScene(document, "rod implicit test", app::makeFactory());
  scene->init();
  return scene;
}

const FramedChain& chainOf(const Scene& scene) { return dynamic_cast<const FramedChain&>(*scene.bodies().front()); }

/// Velocity-layout index of JacobianAccumulator coordinate c (groups: points, then internal triples).
int velocityIndex(const Scene& scene, int c) {
  const int n3 = 3 * scene.dofPointCount();
  return c < n3 ? c : c + scene.extraDofCount();
}

/// K = ∂Q/∂w of every force field, assembled (k_factor 1) and mapped to the velocity layout.
MatX assembledStiffness(const Scene& scene, const SceneState& s) {
  Triplets triplets;
  TripletAccumulator accumulator(triplets);
  for (const ForceField* field : scene.forceFields()) field->addJacobian(s, 1.0, 0.0, accumulator);
  MatX K = MatX::Zero(scene.velocitySize(), scene.velocitySize());
  for (const Triplet& t : triplets) K(velocityIndex(scene, t.row()), velocityIndex(scene, t.col())) += t.value();
  return K;
}

/// The symmetric part of ∂Q/∂w by central differences (h = 1e-7 m or rad: truncation h² |Q'''|,
/// round-off ε |Q| / h).
MatX differencedStiffness(const Scene& scene, const SceneState& s) {
  const int n = scene.velocitySize();
  MatX K(n, n);
  const double h = 1e-7;
  for (int k = 0; k < n; ++k) {
    VecX w = VecX::Zero(n);
    w[k] = 1.0;
    SceneState plus = s, minus = s;
    scene.integratePositions(s.q, w, h, plus.q);
    scene.integratePositions(s.q, w, -h, minus.q);
    K.col(k) = (test::rodForces(scene, plus, 1.0) - test::rodForces(scene, minus, 1.0)) / (2.0 * h);
  }
  return 0.5 * (K + K.transpose());
}

TEST(RodImplicit, JacobianMatchesFiniteDifferences) {
  // A rod with a built-in end, its points moved by up to 0.1 mm (stretch and shear strained).
  //  - Frames at their rest turns (a straight rod, moments zero): every term the Jacobian has is
  //    exact there; it matches the differences' symmetric part to 1e-6 of its largest entry
  //    (central differences at h = 1e-7: truncation and round-off ~1e-8 relative).
  //  - A J-tip rest shape with the frames still straight (moments up to E I κ̄): the bending
  //    term's Gauss–Newton matrix leaves out m · ∂²φ, |∂²φ| <= 1 per unit turn (the derivative
  //    of J⁻¹ = I ± ½ φ̂ + ...), so the difference stays below the largest moment (N·m) plus
  //    the same 1e-6 of the stretch and shear scale.
  const json rest = {{"type", "ChainElasticity"}, {"youngs_modulus", 3e7}, {"spans", {{{"from", 0.75}, {"to", 1.0}, {"rest_curvature", {0.0, 30.0}}}}}};
  json document = rodDocument(6, 3e7, 0.0, {{"type", "ImplicitEuler"}}, json::array({{{"type", "RodEndFrame"}}}), 1e-3, 1e-3);
  document["nodes"][0]["components"][1] = rest;
  auto scene = load(document);
  SceneState s = scene->state();
  std::srand(4);
  VecX w = VecX::Zero(scene->velocitySize());
  w.head(3 * scene->dofPointCount()) = 1e-4 * VecX::Random(3 * scene->dofPointCount());
  scene->integratePositions(s.q, w, 1.0, s.q);
  // The frames start straight while the rest shape is curved: moments |m| <= E I κ̄ at the tip.
  const MatX K = assembledStiffness(*scene, s), fd = differencedStiffness(*scene, s);
  const double scale = fd.cwiseAbs().maxCoeff();
  std::cout << "  |K - K_fd| = " << (K - fd).cwiseAbs().maxCoeff() << " of " << scale << '\n';
  const double moment = 3e7 * kSecond * 30.0;
  EXPECT_LE((K - fd).cwiseAbs().maxCoeff(), moment + 1e-6 * scale);

  auto straight = load(rodDocument(6, 3e7, 0.0, {{"type", "ImplicitEuler"}}, json::array({{{"type", "RodEndFrame"}}}), 1e-3, 1e-3));
  SceneState p = straight->state();
  straight->integratePositions(p.q, w, 1.0, p.q);  // points strained, frames at their rest turns
  const MatX K0 = assembledStiffness(*straight, p), fd0 = differencedStiffness(*straight, p);
  std::cout << "  at rest turns: |K - K_fd| = " << (K0 - fd0).cwiseAbs().maxCoeff() << " of " << fd0.cwiseAbs().maxCoeff() << '\n';
  EXPECT_LE((K0 - fd0).cwiseAbs().maxCoeff(), 1e-6 * fd0.cwiseAbs().maxCoeff());
}

TEST(RodImplicit, ImplicitEulerAtOneMillisecondSettlesOnTheStaticElastica) {
  // Γ = 5, 21 nodes, held at s = 0 (FixedPointConstraint and RodEndFrame), released straight
  // under gravity with drag γ = 10/s, ImplicitEuler at dt = 1 ms for 3 s (ω₁ ≈ 11 rad/s: the
  // swing decays as e^{−γ t/2} ≈ 3e-7 by then, less still with backward Euler's own damping).
  // At rest M a = Q + Lᵀλ = 0 is the static equilibrium of the same discrete rod
  // (support/rod_statics), so the tips agree to the decay left, 3e-7 of the 0.1 m swing:
  // 1e-6 m asserted. (The frames must follow the point constraint through A: without their
  // share of A⁻¹ Lᵀ λ the rod came to rest 4 µm off, with 0.13 N unbalanced.)
  const double E = modulusFor(5.0);
  const json end = json::array({{{"type", "RodEndFrame"}},
                                {{"type", "FixedPointConstraint"}, {"abscissa", 0.0}},
                                {{"type", "ViscousDamping"}, {"coefficient", 10.0}}});
  auto scene = load(rodDocument(21, E, 9.81, {{"type", "ImplicitEuler"}}, end, 1e-3, 3.0));
  for (int k = 0; k < 3000; ++k) {
    const StepReport report = scene->step();
    ASSERT_TRUE(report.ok) << "step " << k << ": " << report.message;
  }
  const Vec3 dynamic = chainOf(*scene).block(scene->state().q).row(20).transpose();
  auto statics = load(rodDocument(21, E, 9.81, {{"type", "RungeKutta4"}}, json::array({{{"type", "RodEndFrame"}}}), 1e-3, 1.0));
  const Vec3 reference = chainOf(*statics).block(test::equilibrium(*statics, 10).q).row(20).transpose();
  std::cout << "  tip after 3 s: " << dynamic.transpose() << ", static " << reference.transpose() << '\n';
  EXPECT_LE((dynamic - reference).norm(), 1e-6);
}

TEST(RodImplicit, BackwardEulerKeepsMomentumAndCreatesNoEnergy) {
  // A free rod (no gravity, no constraint) bent and spun: ImplicitEuler at 1 ms. The forces sum
  // to zero and the step matrix's point rows do too (translation invariance), so Σ m v stays at
  // its start to round-off (1e-12 relative over 200 steps). Backward Euler damps: the energy
  // never grows from one step to the next beyond round-off (1e-12 relative).
  auto scene = load(rodDocument(11, 3e7, 0.0, {{"type", "ImplicitEuler"}}, json::array(), 1e-3, 0.2));
  SceneState s = scene->state();
  std::srand(9);
  VecX w = VecX::Zero(scene->velocitySize());
  w.head(3 * scene->dofPointCount()) = 2e-3 * VecX::Random(3 * scene->dofPointCount());
  scene->integratePositions(s.q, w, 1.0, s.q);
  s.v = 0.2 * VecX::Random(scene->velocitySize());
  scene->setState(s);
  const auto momentum = [&] {
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < chainOf(*scene).pointCount(); ++i)
      p += chainOf(*scene).nodeMass(i) * chainOf(*scene).block(scene->state().v).row(i).transpose();
    return p;
  };
  const Vec3 p0 = momentum();
  double energy = scene->energy(scene->state()).total();
  for (int k = 0; k < 200; ++k) {
    const StepReport report = scene->step();
    ASSERT_TRUE(report.ok) << report.message;
    const double next = scene->energy(scene->state()).total();
    EXPECT_LE(next, energy * (1.0 + 1e-12)) << "step " << k;
    energy = next;
  }
  EXPECT_LE((momentum() - p0).norm(), 1e-12 * p0.norm());
}

TEST(RodImplicit, TheMidpointRuleRefusesARod) {
  try {
    load(rodDocument(5, 3e7, 9.81, {{"type", "ImplicitMidpoint"}}, json::array(), 1e-3, 1e-3));
    ADD_FAILURE() << "ImplicitMidpoint accepted a FramedChain";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("ImplicitEuler or an explicit integrator"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace filum

namespace filum {
namespace {

TEST(RodImplicit, TheStepMatrixsInverseBandHoldsItsInversesPointBlocks) {
  // A rod's step matrix A = M − h D − h² K, its frames' triples interleaved with its points in
  // the band (BandBlocks::point_group): the blocks of A⁻¹ that inverseBandBlocks gives between
  // points within the band are those of the dense inverse of the same assembled matrix. Both are
  // backward-stable inverses of a symmetric positive definite matrix (M dominates at h = 1 ms):
  // they agree to a few ε cond(A) relative, cond(A) computed here; 1e2 ε cond(A) asserted.
  const double h = 1e-3;
  auto scene = load(rodDocument(8, 3e7, 9.81, {{"type", "ImplicitEuler"}}, json::array({{{"type", "RodEndFrame"}}}), h, h));
  SceneState s = scene->state();
  std::srand(5);
  VecX w = VecX::Zero(scene->velocitySize());
  w.head(3 * scene->dofPointCount()) = 1e-4 * VecX::Random(3 * scene->dofPointCount());
  scene->integratePositions(s.q, w, 1.0, s.q);
  mechanics::StepMatrix a;
  ASSERT_EQ(a.assemble(*scene, s, -h * h, -h), "");  // (and factored)
  BandBlocks band;
  std::vector<Eigen::Matrix3d> z;
  ASSERT_TRUE(a.bandBlocks(0, band));
  ASSERT_TRUE(a.inverseBandBlocks(0, 0, z));
  const MatX dense = a.assembledMatrix();
  const MatX inverse = dense.inverse();
  const Eigen::JacobiSVD<MatX> svd(dense);
  const double cond = svd.singularValues()(0) / svd.singularValues()(dense.rows() - 1);
  const int points = scene->dofPointCount();
  int compared = 0;
  double error = 0.0;
  for (int p = 0; p < points; ++p)
    for (int q = 0; q <= p; ++q) {
      const int gp = band.point_group[p], gq = band.point_group[q];
      if (std::abs(gp - gq) > band.range) continue;
      const int hi = std::max(gp, gq), lo = std::min(gp, gq);
      Eigen::Matrix3d block = z[hi * (band.range + 1) + (lo - hi + band.range)];
      if (gp < gq) block.transposeInPlace();  // (p, q) when the stored one is (q, p)
      error = std::max(error, (block - inverse.block<3, 3>(3 * p, 3 * q)).lpNorm<Eigen::Infinity>());
      ++compared;
    }
  std::printf("  %d point blocks within the band; cond(A) %.2g; largest difference %.2g of %.2g\n", compared, cond, error,
              inverse.lpNorm<Eigen::Infinity>());
  EXPECT_GE(compared, 2 * points - 1);  // each point with itself and its neighbour at least
  EXPECT_LE(error, 1e2 * std::numeric_limits<double>::epsilon() * cond * inverse.lpNorm<Eigen::Infinity>());
}

}  // namespace
}  // namespace filum
