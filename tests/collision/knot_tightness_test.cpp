// Knot tightness (collision/knot_tightness.hpp): the thread a knot holds, the contacts inside it
// and their slip.
//   - The span of an open overhand knot: it lies on the knotted part, not on the arms; it is the
//     same thread whatever the arms' length (the closing arc moves, the knot does not), and it
//     scales with the curve (crossing positions along the edges are invariant under scaling).
//   - Slip on a hairpin whose legs touch: one leg moving sideways at u (along z, out of the plane
//     z = 0 the legs and every contact normal lie in), the other at rest: the slip speed is u (the
//     legs' points move with the partition of unity Σ N_j = 1 of the spline basis: exactly u
//     where a point's support is on the moving leg); the whole thread translated: zero (Galilean
//     invariance). Both to round-off. A span that leaves out the bend and part of
//     the legs counts only the contacts with both points inside it.
#include <gtest/gtest.h>

#include <cmath>

#include "collision_scenes.hpp"
#include "filum/collision/knot_determinant.hpp"
#include "filum/collision/knot_tightness.hpp"
#include "filum/collision/knot_type.hpp"

namespace filum::collision {
namespace {

constexpr double kRoundOff = 1e-12;  // relative: sums of a few hundred terms of unit size

/// Arc length of a polyline between two positions (vertex index + fraction of the next edge).
double polylineLength(const Points& line, double from, double to) {
  auto at = [&](double position) {
    const int i = std::min(static_cast<int>(position), static_cast<int>(line.rows()) - 2);
    const double f = position - i;
    return Vec3(((1.0 - f) * line.row(i) + f * line.row(i + 1)).transpose());
  };
  const int a = static_cast<int>(std::ceil(from)), b = static_cast<int>(std::floor(to));
  double length = (line.row(a).transpose() - at(from)).norm() + (at(to) - line.row(b).transpose()).norm();
  for (int i = a; i < b; ++i) length += (line.row(i + 1) - line.row(i)).norm();
  return length;
}

TEST(KnotTightness, PositionsMapToAbscissasAlongEachEdge) {
  const std::vector<double> abscissas = {0.0, 0.5, 2.0};
  EXPECT_DOUBLE_EQ(atPosition(abscissas, 0.5), 0.25);
  EXPECT_DOUBLE_EQ(atPosition(abscissas, 1.5), 1.25);
  EXPECT_DOUBLE_EQ(atPosition(abscissas, 2.0), 2.0);
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
  const KnotType type = knotType(closeFarAway(helix));
  ASSERT_EQ(type.name, "unknot");
  EXPECT_FALSE(knotSpan(type, 200).found);
}

/// A thread folded into a hairpin: two straight legs of 21 control points 2 mm apart along x,
/// joined by one point at the bend; the first leg held by five fixed points, the second lying on
/// it under gravity along −y (radius 1 mm: they start 0.05 mm apart and it falls onto it).
struct Hairpin {
  static constexpr int kLeg = 21;
  std::unique_ptr<Scene> scene;
  Hairpin() {
    nlohmann::json points = nlohmann::json::array();
    for (int i = 0; i < kLeg; ++i) points.push_back({0.002 * i, 0.0, 0.0});
    points.push_back({0.002 * kLeg, 0.001025, 0.0});
    for (int i = kLeg - 1; i >= 0; --i) points.push_back({0.002 * i, 0.00205, 0.0});
    test::CollisionThread thread;
    thread.control_points = points;
    thread.viscous_damping = 50.0;  // 1/s: at rest within the 50 ms run
    for (double s : {0.05, 0.15, 0.25, 0.35, 0.45})
      thread.constraints.push_back({{"type", "FixedPointConstraint"}, {"abscissa", s}});
    scene = test::loadCollisionScene(test::collisionScene(
        {thread}, {{"type", "ContactPipeline"}, {"response", "unilateral"}, {"friction", 0.3}}, 1e-4, nlohmann::json::array(),
        {0.0, -9.81, 0.0}));
    scene->init();
    for (int k = 0; k < 500; ++k) EXPECT_TRUE(scene->step().ok);  // 50 ms: fallen and resting
  }
  /// The tightness over abscissas [s0, s1] (a two-vertex polyline, span from vertex 0 to 1).
  KnotTightness tightnessWith(const VecX& v, double s0 = 0.0, double s1 = 1.0) {
    SceneState s = scene->state();
    s.v.head(v.size()) = v;
    const CurveBody& body = *scene->bodies()[0]->curve();
    KnotSpan span;
    span.found = true;
    span.first = 0.0;
    span.last = 1.0;
    return knotTightness(&test::pipelineOf(*scene), body, {s0, s1}, span, s);
  }
  /// The pressed self-contacts with both abscissas in [s0, s1], counted here.
  int pressedContactsWithin(double s0, double s1) const {
    const collision::ContactPipeline& pipeline = test::pipelineOf(*scene);
    int count = 0;
    for (std::size_t i = 0; i < pipeline.contacts().size(); ++i) {
      const Contact& c = pipeline.contacts()[i];
      if (c.model_b < 0 || pipeline.contactForce(static_cast<int>(i), scene->state()).dot(c.normal) <= 0.0) continue;
      if (c.a.abscissa() >= s0 && c.a.abscissa() <= s1 && c.b.abscissa() >= s0 && c.b.abscissa() <= s1) ++count;
    }
    return count;
  }
};

TEST(KnotTightness, SlipIsTheSpeedOfOneLegAcrossTheOther) {
  Hairpin hairpin;
  const int points = 2 * Hairpin::kLeg + 1;
  const double u = 0.37;  // m/s
  VecX v = VecX::Zero(3 * points);
  // The first leg slides along z, out of the plane z = 0 in which both legs lie (and every
  // normal: n_z = 0 to round-off, so (I − n nᵀ) u ẑ = u ẑ at every contact whose first point's
  // support is on that leg).
  for (int i = 0; i < Hairpin::kLeg; ++i) v[3 * i + 2] = u;
  const KnotTightness sliding = hairpin.tightnessWith(v);
  ASSERT_GT(sliding.contacts, 10) << "the legs touch along their length";
  EXPECT_NEAR(sliding.slip_speed, u, kRoundOff * u);
  EXPECT_EQ(sliding.contacts, hairpin.pressedContactsWithin(0.0, 1.0));
  // A span from s = 0.2 to 0.9: the contacts near the first leg's start (s < 0.2) left out.
  const KnotTightness part = hairpin.tightnessWith(v, 0.2, 0.9);
  EXPECT_EQ(part.contacts, hairpin.pressedContactsWithin(0.2, 0.9));
  EXPECT_LT(part.contacts, sliding.contacts);
  EXPECT_GT(part.contacts, 0);
  // The whole thread carried along at (u, −u, 2u): nothing slides.
  for (int i = 0; i < points; ++i) v.segment<3>(3 * i) = Vec3(u, -u, 2 * u);
  EXPECT_NEAR(hairpin.tightnessWith(v).slip_speed, 0.0, kRoundOff * u);
}

}  // namespace
}  // namespace filum::collision
