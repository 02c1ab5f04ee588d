// TissueAttachment (tissue_attachment.hpp): its force, stiffness and damping against finite
// differences, a tube on a uniform foundation against the exact sag q/k, a cut tube whose two
// parts stay held, the slack of a sheet, and bad input refused with its place.
#include <gtest/gtest.h>

#include <cmath>

#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/mechanics/tissue_attachment.hpp"
#include "support/finite_difference.hpp"
#include "support/force_field_check.hpp"
#include "support/mechanics_scenes.hpp"

namespace filum {
namespace {

using nlohmann::json;

// A fallopian-tube-like soft tube: 10 cm, radius 3 mm, 1050 kg/m³, E = 100 kPa.
constexpr double kLength = 0.1, kRadius = 3e-3, kDensity = 1050.0, kModulus = 1e5;
const double kLinearDensity = kDensity * M_PI * kRadius * kRadius;  // ρA, kg/m

test::ThreadSpec tubeSpec() {
  test::ThreadSpec spec;
  spec.control_points = 12;
  spec.length = kLength;
  spec.radius = kRadius;
  spec.mass = kLinearDensity * kLength;
  spec.dt = 1e-3;
  return spec;
}

json tubeMaterial() {
  return json::array({json{{"type", "GreenLagrangeStretching"}, {"youngs_modulus", kModulus}},
                      json{{"type", "CurvatureBending"}, {"youngs_modulus", kModulus}}});
}

const mechanics::TissueAttachment& attachmentOf(const Scene& scene) {
  for (const ForceField* field : scene.forceFields())
    if (const auto* a = dynamic_cast<const mechanics::TissueAttachment*>(field)) return *a;
  throw std::logic_error("no TissueAttachment in the scene");
}

TEST(TissueAttachment, ForceStiffnessAndDampingMatchFiniteDifferences) {
  // Central differences at h = 1e-7 m on displacements of ~1 mm: truncation h²/6 |f'''| relative
  // ~ (h/|d|)² ~ 1e-8, round-off ε|f|/h ~ 1e-16 · 1e-3 / 1e-7 ~ 1e-12 relative: 1e-6 is safe.
  for (const json& rest : {json(0.0), json("initial")}) {
    json attachment = {{"type", "TissueAttachment"}, {"from", 0.1}, {"to", 0.9}, {"count", 7},
                       {"stiffness", 200.0}, {"damping", 3.0}, {"rest_length", rest},
                       {"root", {{"from", {0.0, 0.0, -0.01}}, {"to", {0.1, 0.0, -0.012}}}}};
    auto scene = test::loadThreadWith(tubeSpec(), json::array({attachment}));
    scene->init();
    SceneState s = scene->state();
    const Points shift = test::randomPoints(12, 2e-3, 7);
    const Points speed = test::randomPoints(12, 0.05, 8);
    for (int j = 0; j < 12; ++j) s.q.segment<3>(3 * j) += shift.row(j).transpose();
    test::ForceFieldCheck check;
    check.h = 1e-7;
    test::expectForceFieldConsistent(attachmentOf(*scene), s, check);  // at rest: Q = −∂E/∂q
    for (int j = 0; j < 12; ++j) s.v.segment<3>(3 * j) = speed.row(j).transpose();
    check.gradient = false;  // moving, Q has the dashpots too: K and D only
    test::expectForceFieldConsistent(attachmentOf(*scene), s, check);
  }
}

// The tube lying straight on a uniform foundation under gravity settles at the sag q/k exactly
// (q = ρ A g): no internal force sums to anything (stretching and bending are translation
// invariant and the basis is a partition of unity), so at rest Σ_i k_i d_i = −m g, i.e. the mean
// sag is q/k to the solver's round-off. Pointwise the springs sample the foundation at the
// midpoints of their pieces, where gravity acts through ∫ρA g b_j ds: the midpoint rule's error,
// (h_piece/h_span)²/24 = (9/40)²/24 ≈ 2.1e-3 here (40 pieces on 9 spans; second derivatives of a
// cubic B-spline are of the size of the function over a span), is the only nonuniform load, and a
// foundation answers a load δq with at most δq/k: every point within 3e-3 of q/k (a factor 1.5
// over the estimate for its constant).
void expectSagOnFoundation(Scene& scene, double k, double seconds) {
  const int steps = static_cast<int>(std::lround(seconds / scene.settings().dt));
  for (int i = 0; i < steps; ++i) ASSERT_TRUE(scene.step().ok);
  const double sag = kLinearDensity * 9.81 / k;
  const auto& attachment = attachmentOf(scene);
  double mean = 0.0;
  for (int i = 0; i < attachment.count(); ++i) {
    const double drop = attachment.anchor(i).z() -
                        scene.bodies().front()->curve()->position(scene.state().q, attachment.abscissa(i)).z();
    mean += drop / attachment.count();
    EXPECT_NEAR(drop, sag, 3e-3 * sag) << "point " << i;
  }
  // The mean: round-off of the implicit solve and of the remaining motion after 40 time
  // constants of the critically damped foundation (e^-40): 1e-9 relative.
  EXPECT_NEAR(mean, sag, 1e-9 * sag);
}

double criticalDamping(double k) { return 2.0 * std::sqrt(k * kLinearDensity); }  // c = 2√(kρA)

TEST(TissueAttachment, ATubeOnAUniformFoundationSinksByItsWeightOverTheModulus) {
  const double k = 100.0;  // Pa: sag q/k = 2.9 mm
  json components = tubeMaterial();
  components.push_back({{"type", "TissueAttachment"}, {"count", 40}, {"stiffness", k}, {"damping", criticalDamping(k)}});
  auto scene = test::loadThreadWith(tubeSpec(), components);
  scene->init();
  // ω = √(k/ρA) = 58 rad/s; critically damped, 40 time constants 1/ω take 0.7 s.
  expectSagOnFoundation(*scene, k, 0.7);
}

TEST(TissueAttachment, ACutTubeKeepsBothPartsHeld) {
  // Settled on its foundation, then cut in the middle: each part is a tube on the same
  // foundation, still sunk by q/k below the anchors of the start (the cut rebinds the field to
  // the new layout; the tissue keeps its anchors and rest lengths).
  const double k = 100.0;
  json components = tubeMaterial();
  components.push_back({{"type", "TissueAttachment"}, {"count", 40}, {"stiffness", k}, {"damping", criticalDamping(k)}});
  auto scene = test::loadThreadWith(tubeSpec(), components);
  scene->init();
  expectSagOnFoundation(*scene, k, 0.7);
  const Vec3 anchor = attachmentOf(*scene).anchor(7);
  scene->cut(*scene->bodies().front()->curve(), 0.5);
  ASSERT_EQ(strands(scene->bodies().front()->curve()->basis()).size(), 2u);
  EXPECT_EQ(attachmentOf(*scene).anchor(7), anchor);
  expectSagOnFoundation(*scene, k, 0.7);
}

TEST(TissueAttachment, ASheetCarriesNoCompression) {
  // rest_length "initial" with a root line 1 cm below: pushed towards the root the sheet goes
  // slack (no force, no energy); pulled away it pulls back along d with k (|d| − r).
  json attachment = {{"type", "TissueAttachment"}, {"count", 3}, {"stiffness", 100.0}, {"rest_length", "initial"},
                     {"root", {{"from", {0.0, 0.0, -0.01}}, {"to", {0.1, 0.0, -0.01}}}}};
  auto scene = test::loadThreadWith(tubeSpec(), json::array({attachment}));
  scene->init();
  const auto& field = attachmentOf(*scene);
  SceneState s = scene->state();
  for (int j = 0; j < 12; ++j) s.q[3 * j + 2] -= 2e-3;  // 2 mm towards the root
  EXPECT_EQ(field.springForce(s, 1), Vec3::Zero());
  EXPECT_EQ(field.potentialEnergy(s), 0.0);
  for (int j = 0; j < 12; ++j) s.q[3 * j + 2] += 5e-3;  // 3 mm away from the rest length
  const double ki = field.pointStiffness();
  EXPECT_NEAR(field.springForce(s, 1).z(), -ki * 3e-3, 1e-12 * ki);
}

TEST(TissueAttachment, BadInputIsRefusedWithItsPlace) {
  auto refusal = [](const json& attachment) {
    try {
      auto scene = test::loadThreadWith(tubeSpec(), json::array({attachment}));
      scene->init();
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const json base = {{"type", "TissueAttachment"}, {"stiffness", 10.0}};
  json a = base;
  a["from"] = 0.6;
  a["to"] = 0.4;
  EXPECT_NE(refusal(a).find("/to"), std::string::npos) << refusal(a);
  a = base;
  a["anchors"] = "root";
  EXPECT_NE(refusal(a).find("/root"), std::string::npos) << refusal(a);
  a = base;
  a["rest_length"] = "slack";
  EXPECT_NE(refusal(a).find("/rest_length"), std::string::npos) << refusal(a);
  a = base;
  a["count"] = 0;
  EXPECT_NE(refusal(a).find("/count"), std::string::npos) << refusal(a);
  a = base;
  a.erase("stiffness");
  EXPECT_NE(refusal(a).find("stiffness"), std::string::npos) << refusal(a);
}

}  // namespace
}  // namespace filum
