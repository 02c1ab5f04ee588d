// The nearest point of a tube's centre line, found through the blocks of AxisBounds (a block
// farther than the nearest point found is skipped), is the brute-force scan's, bit for bit: the
// same chord — the first of equally near ones —, parameter and distance, and the same end test,
// whatever chord it is told to measure first, and without reading the rows of the centres'
// storage beyond the sphere count.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "filum/collision/narrow_phase.hpp"
#include "filum/collision/sphere_sampling_mapping.hpp"
#include "filum/geometry/spline_basis_factory.hpp"

namespace filum::collision {
namespace {

/// A polyline tube axis: a helix-like curve that comes back near itself (a loop), so that far
/// chords along it are near in space, with vertices at unequal spacing.
Points loopedAxis(int vertices) {
  Points q(vertices, 3);
  for (int i = 0; i < vertices; ++i) {
    const double s = i + 0.3 * std::sin(1.7 * i);
    q.row(i) << 0.01 * std::cos(0.11 * s), 0.01 * std::sin(0.11 * s), 2e-4 * s;
  }
  return q;
}

void expectSame(const AxisPoint& a, const AxisPoint& b, const Vec3& x) {
  EXPECT_EQ(a.chord, b.chord) << "at " << x.transpose();
  EXPECT_EQ(a.u, b.u) << "at " << x.transpose();
  EXPECT_EQ(a.distance, b.distance) << "at " << x.transpose();
  EXPECT_EQ(a.radial, b.radial) << "at " << x.transpose();
}

TEST(AxisBounds, TheBlockedSearchFindsTheBruteForceNearestPointBitForBit) {
  geometry::SplineBasisSpec spec;
  spec.name = "nubs";
  spec.degree = 1;
  for (int vertices : {2, 9, 10, 61, 140}) {
    spec.control_points = vertices;
    const auto basis = geometry::makeSplineBasis(spec);
    const Points q = loopedAxis(vertices);
    SphereSamplingMapping mapping(*basis, 1.0);  // (spacing above every piece: the vertices are the centres)
    mapping.resample(q);
    const int count = mapping.outputCount();
    // Held as a model holds its centres: in storage of twice the count, the rows beyond it not
    // the axis's (here NaN and far values, which the bounds must not read).
    Points axis(2 * count, 3);
    axis.bottomRows(count).setConstant(1e3);
    axis(count, 0) = std::numeric_limits<double>::quiet_NaN();
    Points centres(count, 3);
    mapping.apply(q, centres);
    axis.topRows(count) = centres;
    AxisBounds bounds;
    bounds.build(axis, count);
    EXPECT_EQ(bounds.blocks(), (count - 1 + AxisBounds::kChords - 1) / AxisBounds::kChords);
    std::mt19937 random(7 + vertices);
    std::uniform_real_distribution<double> coordinate(-0.014, 0.014), height(-0.002, 0.002 + 2e-4 * vertices);
    std::uniform_int_distribution<int> vertex(0, mapping.outputCount() - 1);
    int compared = 0;
    for (int k = 0; k < 2000; ++k) {
      // Points anywhere around the loop, and points on the axis's vertices (equally near to the
      // two chords sharing one: the first must be taken), each with a hint right, wrong or none.
      const Vec3 x = k % 4 == 3 ? Vec3(centres.row(vertex(random)).transpose())
                                : Vec3(coordinate(random), coordinate(random), height(random));
      const AxisPoint brute = nearestAxisPoint(centres, mapping, x);
      for (int hint : {-1, 0, std::max(0, count - 2), count - 1, count, brute.chord}) {
        expectSame(nearestAxisPoint(axis, mapping, x, &bounds, hint), brute, x);
        ++compared;
      }
    }
    EXPECT_EQ(compared, 12000);
  }
}

}  // namespace
}  // namespace filum::collision
