// Spline junctions ([Lenoir talk 2008], fallopian tubes: three splines joined with C2 continuity, cut by
// releasing a junction) and releases at run time.
#include <gtest/gtest.h>

#include <iostream>

#include <Eigen/Geometry>

#include "filum/constraints/lagrange_multiplier_solver.hpp"
#include "filum/constraints/spline_junction_constraint.hpp"
#include "filum/core/scene.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "support/constraint_scenes.hpp"

namespace filum {
namespace {

using nlohmann::json;
using test::ConstraintThread;

/// Three 4 cm parts along x joined end to start with C^k, the outer ends clamped; the
/// junction between the second and third parts released at `cut` s (none if negative).
json threeParts(int continuity, double cut, int control_points = 7) {
  std::vector<ConstraintThread> parts(3);
  const char* names[] = {"left", "middle", "right"};
  for (int k = 0; k < 3; ++k) {
    parts[k].name = names[k];
    parts[k].control_points = control_points;
    parts[k].length = 0.04;
    parts[k].origin = {0.04 * k, 0.0, 0.0};
  }
  parts[0].constraints.push_back({{"type", "ClampConstraint"}, {"abscissa", 0.0}});
  parts[0].constraints.push_back(
      {{"type", "SplineJunctionConstraint"}, {"name", "left-middle"}, {"other", "middle"}, {"continuity", continuity}});
  json cut_junction = {
      {"type", "SplineJunctionConstraint"}, {"name", "middle-right"}, {"other", "right"}, {"continuity", continuity}};
  if (cut >= 0) cut_junction["release_at"] = cut;
  parts[1].constraints.push_back(cut_junction);
  parts[2].constraints.push_back({{"type", "ClampConstraint"}, {"abscissa", 1.0}});
  return test::constraintScene(parts);
}

const CurveBody& part(const Scene& scene, int k) {
  return *scene.bodies()[k]->curve();
}

/// Geometric jumps across the junction from part a (at s = 1) to part b (at s = 0): position
/// (m), unit tangent (dimensionless) and curvature vector κ n = (P' × P'') × P' / |P'|⁴ (1/m).
struct Jumps {
  double position, tangent, curvature;
};
Jumps jumps(const Scene& scene, int a, int b) {
  const auto da = geometry::curveDerivatives(part(scene, a).basis(), part(scene, a).block(scene.state().q), 1.0);
  const auto db = geometry::curveDerivatives(part(scene, b).basis(), part(scene, b).block(scene.state().q), 0.0);
  auto curvature = [](const geometry::CurveDerivatives& d) {
    return Vec3(d.first.cross(d.second).cross(d.first) / std::pow(d.first.norm(), 4));
  };
  return {(da.point - db.point).norm(), (da.first.normalized() - db.first.normalized()).norm(),
          (curvature(da) - curvature(db)).norm()};
}

TEST(SplineJunction, C2JumpsStayBelow1e8BeforeTheCutAndTheEndsSeparateAfter) {
  // Before the cut every row of both junctions (P, P', P'' in metres per unit abscissa^k) is
  // held like any constraint: RK4's local error pulled back by the Baumgarte terms (measured at
  // round-off, ~1e-15). The geometric jumps follow: unit tangent |Δt̂| <= |ΔP'| / |P'| with
  // |P'| ≈ 0.04 m, curvature |Δκ| ≲ |ΔP''| / |P'|² — factors 25 and 600 above the rows,
  // still far below 1e-8 at round-off level.
  auto scene = test::loadConstraintScene(threeParts(2, 1.0));
  double worst_rows = 0.0;
  Jumps worst{0, 0, 0};
  for (int k = 0; k < 10000; ++k) {
    ASSERT_TRUE(scene->step().ok);
    worst_rows = std::max(worst_rows, scene->constraintViolation(scene->state()).cwiseAbs().maxCoeff());
    for (int j : {0, 1}) {
      const Jumps now = jumps(*scene, j, j + 1);
      worst.position = std::max(worst.position, now.position);
      worst.tangent = std::max(worst.tangent, now.tangent);
      worst.curvature = std::max(worst.curvature, now.curvature);
    }
  }
  std::cout << "  before the cut: rows <= " << worst_rows << " m; jumps: position " << worst.position
            << " m, unit tangent " << worst.tangent << ", curvature " << worst.curvature << " 1/m\n";
  EXPECT_LE(worst_rows, 1e-8);
  EXPECT_LE(worst.position, 1e-8);
  EXPECT_LE(worst.tangent, 1e-8);
  EXPECT_LE(worst.curvature, 1e-8);
  // The tube sags under gravity: the junction is not trivially at rest.
  EXPECT_LT(geometry::curvePoint(part(*scene, 1).basis(), part(*scene, 1).block(scene->state().q), 1.0).z(), -1e-3);

  // The cut (t = 1 s): the middle part's end and the right part's start separate; the other
  // junction and the clamps hold on as before.
  double separation = 0.0, others = 0.0;
  for (int k = 0; k < 3000; ++k) {
    ASSERT_TRUE(scene->step().ok);
    separation = jumps(*scene, 1, 2).position;
    others = std::max(others, scene->constraintViolation(scene->state()).cwiseAbs().maxCoeff());
  }
  std::cout << "  0.3 s after the cut: ends " << separation << " m apart; remaining constraints <= " << others << " m\n";
  EXPECT_GT(separation, 5e-3);
  EXPECT_LE(others, 1e-8);
  EXPECT_LE(jumps(*scene, 0, 1).tangent, 1e-8);
}

TEST(SplineJunction, ReleaseRefactorsNothingAndRestoringAStateRestoresTheJunction) {
  // Releasing removes 9 rows; the other rows' columns M⁻¹ w are reused (no band solve at all in
  // the step after the cut: the mass matrices are constant and never refactored) and a state
  // saved before the cut brings the junction back (releases are a function of the state).
  auto scene = test::loadConstraintScene(threeParts(2, 0.05));
  const auto& solver = dynamic_cast<const constraints::LagrangeMultiplierSolver&>(*scene->constraintSolver());
  for (int k = 0; k < 400; ++k) ASSERT_TRUE(scene->step().ok);
  const SceneState before = scene->state();
  EXPECT_EQ(solver.statistics().rows, 5 + 9 + 9 + 5);
  EXPECT_EQ(solver.statistics().solved_columns, 0);
  for (int k = 0; k < 200; ++k) ASSERT_TRUE(scene->step().ok);
  EXPECT_EQ(solver.statistics().rows, 5 + 9 + 5);
  EXPECT_EQ(solver.statistics().solved_columns, 0) << "the remaining anchors are reused";
  EXPECT_FALSE(scene->constraints()[2]->active());
  scene->setState(before);
  EXPECT_TRUE(scene->constraints()[2]->active());
  ASSERT_TRUE(scene->step().ok);
  EXPECT_EQ(solver.statistics().rows, 5 + 9 + 9 + 5);
}

TEST(SplineJunction, JoinsSplinesOfDifferentLengthsAndResolutions) {
  // A 6 cm thread of 9 control points continued by a 3 cm one of 5: ρ = ℓ1/ℓ2 = 2 scales P'
  // and ρ² = 4 scales P'' so that the common parameter u = ℓ s runs at the same speed on both.
  std::vector<ConstraintThread> parts(2);
  parts[0].control_points = 9;
  parts[0].length = 0.06;
  parts[0].constraints = {json{{"type", "FixedPointConstraint"}, {"abscissa", 0.0}},
                          json{{"type", "SplineJunctionConstraint"}, {"other", "second"}, {"continuity", 2}}};
  parts[1].name = "second";
  parts[1].control_points = 5;
  parts[1].length = 0.03;
  parts[1].origin = {0.06, 0.0, 0.0};
  auto scene = test::loadConstraintScene(test::constraintScene(parts));
  const auto& junction = dynamic_cast<const constraints::SplineJunctionConstraint&>(*scene->constraints()[1]);
  EXPECT_NEAR(junction.ratio(), 2.0, 1e-12);
  double worst = 0.0;
  Jumps geometric{0, 0, 0};
  for (int k = 0; k < 10000; ++k) {
    ASSERT_TRUE(scene->step().ok);
    worst = std::max(worst, scene->constraintViolation(scene->state()).cwiseAbs().maxCoeff());
    const Jumps now = jumps(*scene, 0, 1);
    geometric.tangent = std::max(geometric.tangent, now.tangent);
    geometric.curvature = std::max(geometric.curvature, now.curvature);
  }
  EXPECT_LE(worst, 1e-8);
  EXPECT_LE(geometric.tangent, 1e-8);
  EXPECT_LE(geometric.curvature, 1e-8);
}

TEST(SplineJunction, C0AndC1HoldOnlyWhatTheyAsk) {
  // C0: the position matches, the tangent is free to break; C1: the tangent matches too.
  for (int continuity : {0, 1}) {
    auto scene = test::loadConstraintScene(threeParts(continuity, -1.0));
    for (int k = 0; k < 5000; ++k) ASSERT_TRUE(scene->step().ok);
    const Jumps j = jumps(*scene, 0, 1);
    EXPECT_LE(j.position, 1e-8) << "C" << continuity;
    if (continuity == 0) {
      EXPECT_GT(j.tangent, 1e-3) << "a C0 junction is a hinge: the tube kinks under gravity";
    } else {
      EXPECT_LE(j.tangent, 1e-8);
    }
  }
}

}  // namespace
}  // namespace filum
