// The uniform-grid broad phase finds exactly the overlapping pairs a brute-force search finds, on
// random scenes of every kind (uniform, clustered, mixed radii, automatic and imposed cell
// sizes). The comparison is exact: both use the same predicate |c_i − c_j|² <= (r_i + r_j)², so
// any difference would be a missed or duplicated pair, not round-off.
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "filum/collision/uniform_grid_broad_phase.hpp"

namespace filum::collision {
namespace {

std::vector<BoundingSphere> randomSpheres(int n, double box, double r_min, double r_max, std::mt19937& rng,
                                          bool clustered) {
  std::uniform_real_distribution<double> coord(0.0, box), radius(r_min, r_max), unit(-1.0, 1.0);
  std::vector<BoundingSphere> spheres(n);
  Vec3 cluster = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    if (clustered && i % 50 == 0) cluster = Vec3(coord(rng), coord(rng), coord(rng));
    spheres[i].center = clustered ? Vec3(cluster + 0.05 * box * Vec3(unit(rng), unit(rng), unit(rng)))
                                  : Vec3(coord(rng), coord(rng), coord(rng));
    // Negative coordinates too, so that cell indices straddle zero.
    spheres[i].center -= Vec3::Constant(0.5 * box);
    spheres[i].radius = radius(rng);
  }
  return spheres;
}

TEST(UniformGridBroadPhase, FindsExactlyTheBruteForcePairsOnRandomScenes) {
  std::mt19937 rng(20240611);
  UniformGridBroadPhase automatic;
  std::vector<IndexPair> pairs;
  int scenes = 0;
  long total_pairs = 0;
  for (int n : {2, 10, 100, 1000, 3000})
    for (bool clustered : {false, true})
      for (double r_max : {0.001, 0.01, 0.05}) {
        const auto spheres = randomSpheres(n, 0.2, 0.1 * r_max, r_max, rng, clustered);
        // No budget: these random clusters are far denser than threads (up to ~n²/2 pairs).
        const std::size_t unlimited = std::numeric_limits<std::size_t>::max();
        ASSERT_TRUE(automatic.findPairs(spheres, pairs, unlimited));
        const auto expected = bruteForcePairs(spheres);
        ASSERT_EQ(pairs, expected) << "n = " << n << ", clustered = " << clustered << ", r_max = " << r_max;
        // Cells smaller and larger than the spheres (several cells per sphere, many per cell).
        for (double cell : {0.3 * r_max, 5.0 * r_max}) {
          UniformGridBroadPhase imposed(cell);
          ASSERT_TRUE(imposed.findPairs(spheres, pairs, unlimited));
          ASSERT_EQ(pairs, expected) << "cell = " << cell;
        }
        ++scenes;
        total_pairs += static_cast<long>(expected.size());
      }
  EXPECT_EQ(scenes, 30);
  EXPECT_GT(total_pairs, 10000);  // the scenes are not trivially empty
}

TEST(UniformGridBroadPhase, TouchingSpheresCountAndPairsAreSortedAndUnique) {
  // Two spheres exactly touching (|c1 − c2| = r1 + r2 in binary) and a far one.
  std::vector<BoundingSphere> spheres(3);
  spheres[0] = {Vec3(0.0, 0.0, 0.0), 0.25};
  spheres[1] = {Vec3(0.5, 0.0, 0.0), 0.25};
  spheres[2] = {Vec3(10.0, 0.0, 0.0), 0.25};
  UniformGridBroadPhase grid;
  std::vector<IndexPair> pairs;
  grid.findPairs(spheres, pairs);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], IndexPair(0, 1));
}

TEST(UniformGridBroadPhase, StopsAtItsBudgetWhenEverySphereOverlapsEveryOther) {
  // 1,000 spheres of radius 1 within a cube of side 0.5: all n (n − 1)/2 = 499,500 pairs
  // overlap, far beyond the default budget of 2 · 16 per sphere (32,000). The query stops there,
  // says so, and what it returns is exactly that many true pairs, sorted and unique.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 0.5);
  std::vector<BoundingSphere> spheres(1000);
  for (BoundingSphere& s : spheres) s = {Vec3(u(rng), u(rng), u(rng)), 1.0};
  UniformGridBroadPhase grid;
  std::vector<IndexPair> pairs;
  EXPECT_FALSE(grid.findPairs(spheres, pairs));
  ASSERT_EQ(pairs.size(), 2 * UniformGridBroadPhase::kPairsPerSphere * spheres.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    EXPECT_LT(pairs[k].first, pairs[k].second);
    if (k > 0) {
      EXPECT_LT(pairs[k - 1], pairs[k]);
    }
  }
  // A budget above the true count: complete, and equal to the brute force.
  EXPECT_TRUE(grid.findPairs(spheres, pairs, 500000));
  EXPECT_EQ(pairs, bruteForcePairs(spheres));
}

}  // namespace
}  // namespace filum::collision
