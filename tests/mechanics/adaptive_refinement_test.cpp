// AdaptiveRefinement (adaptive_refinement.hpp) and the layout changes it plans: insertion keeps
// the curve and its velocity to round-off, removal keeps the linear momentum, the plan refines
// where the curve bends or is held and coarsens where it is straight, a thread bent by a load
// gains points and loses them again when it is straightened, and bad input is refused.
#include <gtest/gtest.h>

#include <cmath>

#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"
#include "support/finite_difference.hpp"
#include "support/mechanics_scenes.hpp"

namespace filum {
namespace {

using nlohmann::json;

// A 10 cm 3-0 polypropylene suture (mechanics_scenes.hpp), 12 control points.
test::ThreadSpec sutureSpec() {
  test::ThreadSpec spec;
  spec.control_points = 12;
  spec.dt = 1e-3;
  return spec;
}

json material() {
  return json::array({json{{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}},
                      json{{"type", "CurvatureBending"}, {"youngs_modulus", 2e9}}});
}

std::unique_ptr<Scene> adaptiveThread(json components, const json& adaptivity) {
  components.push_back(adaptivity);
  auto scene = test::loadThreadWith(sutureSpec(), components);
  scene->init();
  return scene;
}

CurveBody& curveOf(Scene& scene) { return *scene.bodies().front()->curve(); }

/// The state with the control points moved by a smooth bend plus noise, and random velocities.
void bendAndMove(Scene& scene) {
  SceneState s = scene.state();
  const int n = curveOf(scene).pointCount();
  const Points noise = test::randomPoints(n, 1e-3, 3), speed = test::randomPoints(n, 0.1, 4);
  for (int j = 0; j < n; ++j) {
    const double x = s.q[3 * j];
    s.q[3 * j + 2] += 0.02 * std::sin(31.4 * x) + noise(j, 2);  // a few bends over the 10 cm
    s.q[3 * j + 1] += noise(j, 1);
    s.v.segment<3>(3 * j) = speed.row(j).transpose();
  }
  scene.setState(s);
}

Vec3 momentum(const Scene& scene) {
  const MechanicalState& body = *scene.bodies().front();
  Points mv(body.pointCount(), 3);
  body.multiplyMass(body.block(scene.state().v), mv);
  return mv.colwise().sum().transpose();  // 1ᵀ M v = ∫ρA Ṗ ds (partition of unity)
}

TEST(AdaptiveRefinement, InsertionKeepsTheCurveAndItsVelocityToRoundOff) {
  auto scene = adaptiveThread(material(), {{"type", "AdaptiveRefinement"}, {"refine_angle", 0.05}});
  bendAndMove(*scene);
  LayoutController::Plan plan;
  scene->layoutControllers().front()->plan(*scene, plan);
  ASSERT_FALSE(plan.insert.empty());
  std::vector<Vec3> before_x, before_v;
  for (int k = 0; k <= 200; ++k) {
    before_x.push_back(curveOf(*scene).position(scene->state().q, k / 200.0));
    before_v.push_back(curveOf(*scene).position(scene->state().v, k / 200.0));  // Ṗ(s) = Σ b_j(s) v_j
  }
  const double x_scale = scene->state().q.cwiseAbs().maxCoeff(), v_scale = scene->state().v.cwiseAbs().maxCoeff();
  const int n = curveOf(*scene).pointCount();
  scene->refine(curveOf(*scene), plan.insert);
  EXPECT_EQ(curveOf(*scene).pointCount(), n + static_cast<int>(plan.insert.size()));
  // Each new control point is a convex combination of old ones (Oslo insertion): a few rounding
  // errors of ε|q| each, and P(s) sums four of them again: 16 ε relative bounds it.
  const double eps = std::numeric_limits<double>::epsilon();
  for (int k = 0; k <= 200; ++k) {
    EXPECT_LE((curveOf(*scene).position(scene->state().q, k / 200.0) - before_x[k]).norm(), 16 * eps * x_scale) << k;
    EXPECT_LE((curveOf(*scene).position(scene->state().v, k / 200.0) - before_v[k]).norm(), 16 * eps * v_scale) << k;
  }
}

TEST(AdaptiveRefinement, RemovalKeepsTheLinearMomentum) {
  auto scene = adaptiveThread(material(), {{"type", "AdaptiveRefinement"}});
  bendAndMove(*scene);
  // A knot of the bent curve removed with a tolerance that accepts any fit: ṽ = R v is a
  // least-squares fit, and the scene adds the uniform velocity that gives back p = 1ᵀ M v.
  const std::vector<double> knots = curveOf(*scene).basis().breakpoints();
  const Vec3 p = momentum(*scene);
  ASSERT_TRUE(scene->coarsen(curveOf(*scene), knots[knots.size() / 2], 1.0));
  // Round-off of the sums 1ᵀ M v over ~12 points of |M v| <= m |v|: 1e-14 of m |v|∞.
  const double scale = scene->bodies().front()->curve()->mass() * 0.1;
  EXPECT_LE((momentum(*scene) - p).norm(), 1e-14 * scale);
}

TEST(AdaptiveRefinement, ThePlanRefinesWhereTheCurveBendsOrIsHeldAndCoarsensWhereItIsStraight) {
  // A straight thread with a 90° kink between x = 4.5 and 5.5 cm (control points 5 and 6 lifted),
  // and with min_span a fixed point at s = 0 asks for short spans there.
  auto scene = adaptiveThread(
      [] {
        json c = material();
        c.push_back({{"type", "FixedPointConstraint"}, {"abscissa", 0.0}});
        return c;
      }(),
      {{"type", "AdaptiveRefinement"}, {"refine_angle", 0.2}, {"coarsen_angle", 0.01}, {"min_span", 0.004},
       {"min_points", 4}});
  SceneState s = scene->state();
  s.q[3 * 5 + 2] += 0.01;
  s.q[3 * 6 + 2] += 0.01;
  scene->setState(s);
  LayoutController::Plan plan;
  scene->layoutControllers().front()->plan(*scene, plan);
  const std::vector<double> knots = curveOf(*scene).basis().breakpoints();
  ASSERT_FALSE(plan.insert.empty());
  bool at_hold = false;
  for (const double u : plan.insert) {
    // Where the kink bends the curve (the B-spline spreads it over the spans the lifted points
    // touch: 3 to 9 of the 9 spans' abscissas 2/9 .. 7/9), or the span of the held point.
    const bool in_kink = u > 2.0 / 9 && u < 7.0 / 9, in_first = u < knots[1];
    EXPECT_TRUE(in_kink || in_first) << "inserted at " << u;
    at_hold = at_hold || in_first;
  }
  EXPECT_TRUE(at_hold);
  // Removals only between straight, untouched spans: beyond the kink's reach (the lifted points
  // 5 and 6 move the spans up to abscissa 8/9), away from the held end's span.
  for (const double u : plan.remove) EXPECT_GT(u, 8.0 / 9 - 1e-12) << u;
  EXPECT_FALSE(plan.remove.empty());
}

TEST(AdaptiveRefinement, AThreadBentByALoadGainsPointsAndLosesThemWhenStraightened) {
  // Held at both ends; the far end brought 4 cm closer and a 10 mN load at the middle bend it
  // (0.3–0.7 s), then the load goes and the end returns (0.7–0.9 s): the thread is straight again.
  json c = material();
  c.push_back({{"type", "ViscousDamping"}, {"coefficient", 5.0}});
  c.push_back({{"type", "FixedPointConstraint"}, {"abscissa", 0.0}});
  c.push_back({{"type", "FixedPointConstraint"},
               {"abscissa", 1.0},
               {"path", {{{"time", 0.0}, {"position", {0.1, 0, 0}}}, {{"time", 0.3}, {"position", {0.06, 0, 0}}},
                         {{"time", 0.7}, {"position", {0.06, 0, 0}}}, {{"time", 0.9}, {"position", {0.0998, 0, 0}}}}}});
  c.push_back({{"type", "PointLoad"},
               {"abscissa", 0.5},
               {"path", {{{"time", 0.0}, {"force", {0, 0, 0}}}, {{"time", 0.3}, {"force", {0, 0, -0.01}}},
                         {{"time", 0.7}, {"force", {0, 0, -0.01}}}, {{"time", 0.8}, {"force", {0, 0, 0}}}}}});
  auto scene = adaptiveThread(c, {{"type", "AdaptiveRefinement"}, {"refine_angle", 0.3}, {"max_points", 20}});
  int most = 0;
  for (int k = 0; k < 1000; ++k) {
    ASSERT_TRUE(scene->step().ok) << k;
    most = std::max(most, curveOf(*scene).pointCount());
    if (k == 699) {
      EXPECT_GT(curveOf(*scene).pointCount(), 12) << "bent under the load";
    }
  }
  EXPECT_LE(most, 20);                                 // max_points
  EXPECT_EQ(curveOf(*scene).pointCount(), 12);         // back to min_points, the initial count
  EXPECT_GT(scene->adaptiveInsertions(), 0);
  EXPECT_EQ(scene->adaptiveRemovals(), scene->adaptiveInsertions());
}

TEST(AdaptiveRefinement, BadSettingsAreRefusedWithTheirPlace) {
  auto refusal = [](const json& settings) {
    try {
      adaptiveThread(material(), settings);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const json base = {{"type", "AdaptiveRefinement"}};
  json a = base;
  a["coarsen_angle"] = 0.1;  // above refine_angle / 4 = 0.0625
  EXPECT_NE(refusal(a).find("/coarsen_angle"), std::string::npos) << refusal(a);
  a = base;
  a["refine_angle"] = 4.0;
  EXPECT_NE(refusal(a).find("/refine_angle"), std::string::npos) << refusal(a);
  a = base;
  a["min_points"] = 30;
  a["max_points"] = 20;
  EXPECT_NE(refusal(a).find("/min_points"), std::string::npos) << refusal(a);
  a = base;
  a["every"] = 0;
  EXPECT_NE(refusal(a).find("/every"), std::string::npos) << refusal(a);
}

}  // namespace
}  // namespace filum
