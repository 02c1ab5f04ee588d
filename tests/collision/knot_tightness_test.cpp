// Knot tightness (collision/knot_tightness.hpp): the thread a knot holds, the contacts inside it
// and their slip.
//   - Polyline lengths against a regular polygon's chords, 2 R sin(π/m) each (exact geometry).
//   - The span of an open overhand knot: it lies on the knotted part, not on the arms; it is the
//     same thread whatever the arms' length (the closing arc moves, the knot does not), and it
//     scales with the curve (crossing positions along the edges are invariant under scaling).
//   - Slip on a hairpin whose legs touch: one leg moving along itself at u, the other at rest:
//     the slip speed is u (the legs' points move with the partition of unity Σ N_j = 1 of the
//     spline basis: exactly u where a point's support is on the moving leg); the whole thread
//     translated: zero (Galilean invariance). Both to round-off.
#include <gtest/gtest.h>

#include <cmath>

#include "collision_scenes.hpp"
#include "filum/collision/knot_determinant.hpp"
#include "filum/collision/knot_tightness.hpp"
#include "filum/collision/knot_type.hpp"

namespace filum::collision {
namespace {

constexpr double kRoundOff = 1e-12;  // relative: sums of a few hundred terms of unit size

TEST(KnotTightness, PolylineLengthIsTheSumOfChords) {
  const int m = 36;
  const double radius = 0.02;
  Points circle(m + 1, 3);
  for (int i = 0; i <= m; ++i) circle.row(i) << radius * std::cos(2 * M_PI * i / m), radius * std::sin(2 * M_PI * i / m), 0.0;
  const double chord = 2 * radius * std::sin(M_PI / m);
  EXPECT_NEAR(polylineLength(circle, 0.0, m), m * chord, kRoundOff * radius);
  EXPECT_NEAR(polylineLength(circle, 2.5, 7.25), 4.75 * chord, kRoundOff * radius);  // partial edges: their fraction
  EXPECT_NEAR(polylineLength(circle, 7.25, 2.5), 4.75 * chord, kRoundOff * radius);
  EXPECT_NEAR(polylineLength(circle, 3.2, 3.7), 0.5 * chord, kRoundOff * radius);
  const std::vector<double> abscissas = {0.0, 0.5, 2.0};
  EXPECT_DOUBLE_EQ(atPosition(abscissas, 0.5), 0.25);
  EXPECT_DOUBLE_EQ(atPosition(abscissas, 1.5), 1.25);
}

Vec3 trefoil(double t) { return Vec3(std::sin(t) + 2 * std::sin(2 * t), std::cos(t) - 2 * std::cos(2 * t), -std::sin(3 * t)); }

/// The trefoil opened at its outer lobe t = π (n points), straight arms of `arm` points, 0.25
/// apart, along −x and +x, tilted down.
Points openOverhand(int n, int arm, double scale) {
  Points open(n + 2 * arm, 3);
  for (int k = 0; k < n; ++k) open.row(arm + k) = scale * trefoil(M_PI + 0.05 + (2 * M_PI - 0.1) * k / (n - 1)).transpose();
  const Eigen::RowVector3d left = scale * Eigen::RowVector3d(-0.25, 0.0, -0.1), right = scale * Eigen::RowVector3d(0.25, 0.0, -0.1);
  for (int k = 1; k <= arm; ++k) {
    open.row(arm - k) = open.row(arm) + k * left;
    open.row(arm + n - 1 + k) = open.row(arm + n - 1) + k * right;
  }
  return open;
}

TEST(KnotTightness, TheKnotsSpanIsOnTheKnotNotOnItsArms) {
  const int n = 90;
  for (int arm : {4, 20, 60}) {
    const Points open = openOverhand(n, arm, 1.0);
    const KnotType type = knotType(closeFarAway(open));
    ASSERT_EQ(type.name, "trefoil") << arm;
    const KnotSpan span = knotSpan(type, static_cast<int>(open.rows()));
    ASSERT_TRUE(span.found);
    EXPECT_GE(span.first, arm) << "the span starts on the knotted part";
    EXPECT_LE(span.last, arm + n - 1) << "and ends on it";
  }
  // The same knot with arms of 4 and of 60 points: the same thread held, to round-off.
  const Points short_arms = openOverhand(n, 4, 1.0), long_arms = openOverhand(n, 60, 1.0);
  const KnotSpan a = knotSpan(knotType(closeFarAway(short_arms)), static_cast<int>(short_arms.rows()));
  const KnotSpan b = knotSpan(knotType(closeFarAway(long_arms)), static_cast<int>(long_arms.rows()));
  const double held = polylineLength(short_arms, a.first, a.last);
  EXPECT_NEAR(polylineLength(long_arms, b.first, b.last), held, kRoundOff * held);
  // Scaled by 1e-3 (a knot of millimetres): the held length scales with it.
  const Points small = openOverhand(n, 4, 1e-3);
  const KnotSpan c = knotSpan(knotType(closeFarAway(small)), static_cast<int>(small.rows()));
  EXPECT_NEAR(polylineLength(small, c.first, c.last), 1e-3 * held, kRoundOff * 1e-3 * held);
  // The held thread is a part of the knotted one, and more than the half of it a trefoil
  // diagram spans (its 6 passages are spread over the whole closed loop).
  const double knotted = polylineLength(short_arms, 4, 4 + n - 1);
  EXPECT_LE(held, knotted);
  EXPECT_GT(held, 0.5 * knotted);
}

TEST(KnotTightness, TheUnknotHoldsNoThread) {
  Points helix(200, 3);
  for (int k = 0; k < 200; ++k) helix.row(k) << std::cos(0.3 * k), std::sin(0.3 * k), 0.02 * k;
  EXPECT_FALSE(knotSpan(knotType(closeFarAway(helix)), 200).found);
}

/// A thread folded into a hairpin: two straight legs of 21 control points 2 mm apart along x,
/// 1.9 mm apart in y (radius 1 mm: they overlap by 0.1 mm), joined by one point at the bend.
struct Hairpin {
  static constexpr int kLeg = 21;
  std::unique_ptr<Scene> scene;
  Hairpin() {
    nlohmann::json points = nlohmann::json::array();
    for (int i = 0; i < kLeg; ++i) points.push_back({0.002 * i, 0.0, 0.0});
    points.push_back({0.002 * kLeg, 0.00095, 0.0});
    for (int i = kLeg - 1; i >= 0; --i) points.push_back({0.002 * i, 0.0019, 0.0});
    test::CollisionThread thread;
    thread.control_points = points;
    thread.viscous_damping = 0.0;
    scene = test::loadCollisionScene(test::collisionScene(
        {thread}, {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"friction", 0.3}}, 1e-4, nlohmann::json::array(),
        {0.0, 0.0, 0.0}));
    scene->init();
    EXPECT_TRUE(scene->step().ok);  // detects the legs' contacts
  }
  KnotTightness tightnessWith(const VecX& v) {
    SceneState s = scene->state();
    s.v.head(v.size()) = v;
    const CurveBody& body = *scene->bodies()[0]->curve();
    const Points line = Points::Zero(2, 3);
    KnotSpan whole;
    whole.found = true;
    whole.first = 0.0;
    whole.last = 1.0;
    return knotTightness(&test::pipelineOf(*scene), body, line, {0.0, 1.0}, whole, s);
  }
};

TEST(KnotTightness, SlipIsTheSpeedOfOneLegAlongTheOther) {
  Hairpin hairpin;
  const int points = 2 * Hairpin::kLeg + 1;
  const double u = 0.37;  // m/s
  VecX v = VecX::Zero(3 * points);
  for (int i = 0; i < Hairpin::kLeg; ++i) v[3 * i] = u;  // the first leg slides along x
  const KnotTightness sliding = hairpin.tightnessWith(v);
  ASSERT_GT(sliding.contacts, 10) << "the legs touch along their length";
  EXPECT_NEAR(sliding.slip_speed, u, kRoundOff * u);
  // The whole thread carried along at (u, −u, 2u): nothing slides.
  for (int i = 0; i < points; ++i) v.segment<3>(3 * i) = Vec3(u, -u, 2 * u);
  EXPECT_NEAR(hairpin.tightnessWith(v).slip_speed, 0.0, kRoundOff * u);
}

}  // namespace
}  // namespace filum::collision
