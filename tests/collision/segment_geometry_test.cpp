// Segment geometry of thread–thread contacts: closest points of two segments against a dense
// brute-force search, and continuous detection of moving segments against dense sampling of the
// motion.
#include <random>

#include <gtest/gtest.h>

#include "filum/collision/segment_closest_points.hpp"
#include "filum/collision/segment_continuous_collision.hpp"

namespace filum::collision {
namespace {

Vec3 randomPoint(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return Vec3(u(rng), u(rng), u(rng));
}

TEST(SegmentClosestPoints, MatchesABruteForceSearch) {
  // Brute force on a 400 × 400 grid of (s, t) then a local refinement grid; the distance is a
  // convex function of (s, t), so the grid minimum is within (Δ/2)·(|d1| + |d2|) of the true one
  // and the exact answer must not be larger than it (it is the minimum).
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 p0 = randomPoint(rng), p1 = randomPoint(rng), q0 = randomPoint(rng);
    Vec3 q1 = randomPoint(rng);
    if (trial % 10 == 0) q1 = q0 + 0.7 * (p1 - p0);  // parallel
    const SegmentClosestPoints c = closestPointsOnSegments(p0, p1, q0, q1);
    EXPECT_NEAR(c.distance, (c.p - c.q).norm(), 1e-15);
    EXPECT_GE(c.s, 0.0);
    EXPECT_LE(c.s, 1.0);
    double best = std::numeric_limits<double>::infinity();
    const int n = 400;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const double s = double(i) / n, t = double(j) / n;
        best = std::min(best, ((p0 + s * (p1 - p0)) - (q0 + t * (q1 - q0))).norm());
      }
    const double resolution = (0.5 / n) * ((p1 - p0).norm() + (q1 - q0).norm());
    EXPECT_LE(c.distance, best + 1e-14);
    EXPECT_GE(c.distance, best - resolution);
  }
}

TEST(SegmentContinuousCollision, FindsEveryCrossingThatDenseSamplingFinds) {
  // Random moving segments; the reference: the sign of the line distance (q − p)·(d1 × d2) over
  // 2000 sub-steps flips with the closest points inside both segments (a crossing), or the
  // sampled distance gets below 1e-9. Every crossing found by sampling must be found by the
  // cubic, and every τ the cubic returns must be a true contact (distance <= tolerance).
  std::mt19937 rng(11);
  int crossings = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    MovingSegment a{randomPoint(rng), randomPoint(rng), Vec3::Zero(), Vec3::Zero()};
    MovingSegment b{randomPoint(rng), randomPoint(rng), Vec3::Zero(), Vec3::Zero()};
    a.end0 = a.start0 + 0.8 * randomPoint(rng);
    a.end1 = a.start1 + 0.8 * randomPoint(rng);
    b.end0 = b.start0 + 0.8 * randomPoint(rng);
    b.end1 = b.start1 + 0.8 * randomPoint(rng);
    const std::optional<double> tau = firstSegmentContact(a, b, 1e-9);
    if (tau) {
      const double t = *tau;
      const SegmentClosestPoints c =
          closestPointsOnSegments(a.start0 + t * (a.end0 - a.start0), a.start1 + t * (a.end1 - a.start1),
                                  b.start0 + t * (b.end0 - b.start0), b.start1 + t * (b.end1 - b.start1));
      EXPECT_LE(c.distance, 1e-9);
    }
    // Dense sampling of the sign of the line distance with interior closest points.
    bool sampled = false;
    double previous = 0.0;
    bool previous_interior = false;
    const int n = 2000;
    for (int k = 0; k <= n && !sampled; ++k) {
      const double t = double(k) / n;
      const Vec3 p0 = a.start0 + t * (a.end0 - a.start0), p1 = a.start1 + t * (a.end1 - a.start1);
      const Vec3 q0 = b.start0 + t * (b.end0 - b.start0), q1 = b.start1 + t * (b.end1 - b.start1);
      const SegmentClosestPoints c = closestPointsOnSegments(p0, p1, q0, q1);
      const bool interior = c.s > 1e-3 && c.s < 1 - 1e-3 && c.t > 1e-3 && c.t < 1 - 1e-3;
      const double signed_distance = signedLineDistance(p0, p1, q0, q1);
      // A crossing passes the line distance continuously through 0 (a rotation through parallel
      // flips its sign with a jump of twice the distance between the lines instead).
      if (k > 0 && interior && previous_interior && (signed_distance > 0) != (previous > 0) &&
          std::abs(signed_distance) + std::abs(previous) < 1e-2)
        sampled = true;
      previous = signed_distance;
      previous_interior = interior;
    }
    if (sampled) {
      ++crossings;
      EXPECT_TRUE(tau.has_value()) << "trial " << trial << ": a crossing found by sampling was missed";
    }
  }
  EXPECT_GT(crossings, 100);  // the random motions do cross often
}

TEST(SegmentContinuousCollision, TwoThreadsSweptAcrossEachOther) {
  // Segment a along x at z = 0; segment b along y moving from z = +1 to z = −1 crosses it at τ = ½.
  const MovingSegment a{Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(1, 0, 0)};
  const MovingSegment b{Vec3(0, -1, 1), Vec3(0, 1, 1), Vec3(0, -1, -1), Vec3(0, 1, -1)};
  const auto tau = firstSegmentContact(a, b, 1e-12);
  ASSERT_TRUE(tau.has_value());
  EXPECT_NEAR(*tau, 0.5, 1e-14);
  // Shifted sideways beyond the end of a: no crossing.
  const MovingSegment c{Vec3(2, -1, 1), Vec3(2, 1, 1), Vec3(2, -1, -1), Vec3(2, 1, -1)};
  EXPECT_FALSE(firstSegmentContact(a, c, 1e-12).has_value());
}

}  // namespace
}  // namespace filum::collision
