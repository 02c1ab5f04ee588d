// Knot types by the Jones polynomial (collision/knot_type.hpp) on synthetic curves: the unknot
// drawn with many crossings, the trefoil and its mirror, the figure-eight, and the two knots a
// surgeon ties by two throws — the square knot (throws of opposite handedness, amphichiral) and
// the granny (the same handedness; its mirror is still a granny) — which the determinant cannot
// tell apart (9 for both); and stitches tied on tissue by throws (single, double; the surgeon's
// knot), named and counted.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "filum/collision/knot_determinant.hpp"
#include "filum/collision/knot_type.hpp"

namespace filum::collision {
namespace {

Vec3 trefoil(double t) { return Vec3(std::sin(t) + 2 * std::sin(2 * t), std::cos(t) - 2 * std::cos(2 * t), -std::sin(3 * t)); }
Vec3 figureEight(double t) {
  return Vec3((2 + std::cos(2 * t)) * std::cos(3 * t), (2 + std::cos(2 * t)) * std::sin(3 * t), std::sin(4 * t));
}
/// The (1, 5) torus curve: an unknot that winds five times round a torus (many crossings in
/// most projections).
Vec3 coiledUnknot(double t) {
  return Vec3((2 + std::cos(5 * t)) * std::cos(t), (2 + std::cos(5 * t)) * std::sin(t), std::sin(5 * t));
}

Points sampleClosed(const std::function<Vec3(double)>& f, int m, double phase = 0.0) {
  Points p(m, 3);
  for (int i = 0; i < m; ++i) p.row(i) = f(phase + 2 * M_PI * i / m).transpose();
  return p;
}

/// The connected sum of two copies of the trefoil, the second mirrored (z → −z) or not: each
/// copy cut open at its outermost point facing the other, the copies 8 apart along x, their cut
/// ends joined by two parallel bridges.
Points twoThrows(bool mirror_second) {
  const int m = 120;
  const Points a = sampleClosed(trefoil, m, 0.0137);
  // The vertex of largest x of the first copy and of smallest x of the second: the cuts.
  int cut_a = 0, cut_b = 0;
  for (int i = 0; i < m; ++i) {
    if (a(i, 0) > a(cut_a, 0)) cut_a = i;
    if (a(i, 0) < a(cut_b, 0)) cut_b = i;
  }
  Points sum(2 * m, 3);
  int row = 0;
  // First copy, at x − 4, from the vertex after the cut round to the cut.
  for (int k = 1; k <= m; ++k) {
    const int i = (cut_a + k) % m;
    sum.row(row++) = Vec3(a(i, 0) - 4, a(i, 1), a(i, 2)).transpose();
  }
  // Bridge to the second copy, at x + 4, from its cut round to the vertex before it. Mirrored,
  // it is run in the direction that keeps the bridges parallel (the mirror of the cut point is
  // the same point in x and y).
  for (int k = 0; k < m; ++k) {
    const int i = (cut_b - k + m) % m;
    const double z = mirror_second ? -a(i, 2) : a(i, 2);
    sum.row(row++) = Vec3(a(i, 0) + 4, a(i, 1), z).transpose();
  }
  return sum;
}

TEST(KnotType, TheUnknotDrawnWithManyCrossings) {
  const KnotType k = knotType(sampleClosed(coiledUnknot, 300));
  EXPECT_EQ(k.name, "unknot") << toString(k.jones);
}

TEST(KnotType, TheTrefoilAndItsMirror) {
  const Points right = sampleClosed(trefoil, 150);
  const KnotType k = knotType(right);
  EXPECT_EQ(k.name, "trefoil") << toString(k.jones);
  EXPECT_EQ(k.crossings, 3);
  Points left = right;
  left.col(2) *= -1.0;
  const KnotType m = knotType(left);
  EXPECT_EQ(m.name, "trefoil");
  EXPECT_NE(m.mirrored, k.mirrored);  // chiral: the mirror has V(1/t)
}

TEST(KnotType, TheFigureEight) {
  const KnotType k = knotType(sampleClosed(figureEight, 200));
  EXPECT_EQ(k.name, "figure-eight") << toString(k.jones);
}

TEST(KnotType, SquareAndGrannyKnotsAreToldApart) {
  const Points square = twoThrows(true), granny = twoThrows(false);
  // Both have determinant 9: |Δ(−1)| cannot tell them apart.
  EXPECT_EQ(knotDeterminant(square), 9);
  EXPECT_EQ(knotDeterminant(granny), 9);
  const KnotType s = knotType(square), g = knotType(granny);
  EXPECT_EQ(s.name, "square") << toString(s.jones);
  EXPECT_EQ(g.name, "granny") << toString(g.jones);
  // The granny tied the other way round (both throws mirrored) is a granny still.
  Points other = granny;
  other.col(2) *= -1.0;
  const KnotType o = knotType(other);
  EXPECT_EQ(o.name, "granny");
  EXPECT_NE(o.mirrored, g.mirrored);
  // The square knot is its own mirror.
  Points square_mirror = square;
  square_mirror.col(2) *= -1.0;
  EXPECT_EQ(knotType(square_mirror).name, "square");
}

TEST(KnotType, AnOpenOverhandKnotClosedFarAwayIsATrefoilAndACoilAnUnknot) {
  // The trefoil opened at its outer lobe t = π, with straight arms carried out along ±x (as in
  // knot_determinant_test.cpp), and a helix (coiled, not knotted).
  const int n = 90;
  Points open(n + 2, 3);
  for (int k = 0; k < n; ++k) open.row(k + 1) = trefoil(M_PI + 0.05 + (2 * M_PI - 0.1) * k / (n - 1)).transpose();
  open.row(0) = (open.row(1) + Eigen::RowVector3d(-5.0, 0.0, -2.0));
  open.row(n + 1) = (open.row(n) + Eigen::RowVector3d(5.0, 0.0, -2.0));
  EXPECT_EQ(knotType(closeFarAway(open)).name, "trefoil");
  Points helix(200, 3);
  for (int k = 0; k < 200; ++k) helix.row(k) << std::cos(0.3 * k), std::sin(0.3 * k), 0.02 * k;
  EXPECT_EQ(knotType(closeFarAway(helix)).name, "unknot");
}

/// One throw of a suture: `wraps` turns of one strand round the other (a single throw 1, the
/// double throw of a surgeon's knot 2), in the sense `sense` (±1).
struct Throw {
  int wraps, sense;
};

/// A stitch tied as on tissue: the thread's bight passes under the wound (z < 0); its two strands
/// rise from x = ∓1 and are tied by the throws, one above the other. In a throw at height h, the
/// strand on the left winds round a horizontal axis (y = 0, z = h) as a helix of radius 0.5,
/// from the bottom of the axis at its x to the top at the other side's x, turning (2k + 1)π
/// (k wraps, then over to the top); the strand on the right runs along the axis the other way.
/// Each throw thus swaps the strands' sides, as pulling a throw tight does. The tails end up and
/// apart; closeFarAway joins them far off.
Points suture(const std::vector<Throw>& throws) {
  std::vector<Vec3> left{Vec3(-1, 0, 0)}, right{Vec3(1, 0, 0)};
  const auto lineTo = [](std::vector<Vec3>& strand, const Vec3& q) {
    const Vec3 a = strand.back();
    for (int i = 1; i <= 10; ++i) strand.push_back(a + (q - a) * (i / 10.0));
  };
  double h = 1.0;
  for (const Throw& t : throws) {
    std::vector<Vec3>& winding = left.back().x() < 0 ? left : right;
    std::vector<Vec3>& straight = left.back().x() < 0 ? right : left;
    lineTo(winding, Vec3(-1, 0, h - 0.5));
    lineTo(straight, Vec3(1, 0, h - 0.5));
    lineTo(straight, Vec3(1, 0, h));
    const int samples = 100 * (2 * t.wraps + 1);
    for (int i = 1; i <= samples; ++i) {
      const double u = static_cast<double>(i) / samples, angle = t.sense * (2 * t.wraps + 1) * M_PI * u;
      winding.push_back(Vec3(-1 + 2 * u, 0.5 * std::sin(angle), h - 0.5 * std::cos(angle)));
    }
    lineTo(straight, Vec3(-1, 0, h));
    lineTo(straight, Vec3(-1, 0, h + 0.5));
    h += 1.5;
  }
  for (std::vector<Vec3>* strand : {&left, &right}) lineTo(*strand, Vec3(3 * strand->back().x(), 0, h + 2));
  std::vector<Vec3> thread(left.rbegin(), left.rend());
  for (int i = 1; i < 20; ++i) {  // the bight under the wound, from x = −1 to x = 1
    const double a = M_PI + M_PI * i / 20;
    thread.push_back(Vec3(std::cos(a), 0.3 * std::sin(a), 0.5 * std::sin(a)));
  }
  thread.insert(thread.end(), right.begin(), right.end());
  Points p(static_cast<int>(thread.size()), 3);
  for (std::size_t i = 0; i < thread.size(); ++i) p.row(static_cast<int>(i)) = thread[i].transpose();
  return p;
}

KnotType typeOfSuture(const std::vector<Throw>& throws) { return knotType(closeFarAway(suture(throws))); }

TEST(KnotType, ThrowsTiedOnTissueAreNamedAndCounted) {
  // No throw: the bight through the tissue alone is no knot.
  EXPECT_EQ(typeOfSuture({}).name, "unknot");
  // A single throw, closed far away, is the overhand knot: the trefoil, its sense its handedness.
  const KnotType single = typeOfSuture({{1, 1}}), single_other = typeOfSuture({{1, -1}});
  EXPECT_EQ(single.name, "trefoil");
  EXPECT_EQ(single.throws, std::vector<int>({1}));
  EXPECT_EQ(single_other.throws, std::vector<int>({-1}));
  EXPECT_NE(single.mirrored, single_other.mirrored);
  // A double throw alone is the (2, 5) torus knot 5₁: V from the knot tables (the Knot Atlas's
  // 5₁ with q → 1/t), not from the formula the code uses.
  const KnotType cinquefoil = typeOfSuture({{2, 1}});
  EXPECT_EQ(cinquefoil.name, "cinquefoil");
  EXPECT_EQ(cinquefoil.jones, LaurentPolynomial({{2, 1}, {4, 1}, {5, -1}, {6, 1}, {7, -1}}));
  // Two single throws: of opposite senses the square knot, of the same sense the granny; the
  // granny tied the other way round (both throws reversed) is its mirror, a granny still.
  const KnotType square = typeOfSuture({{1, 1}, {1, -1}});
  EXPECT_EQ(square.name, "square") << toString(square.jones);
  EXPECT_EQ(square.throws, std::vector<int>({1, -1}));
  EXPECT_EQ(typeOfSuture({{1, -1}, {1, 1}}).name, "square");
  const KnotType granny = typeOfSuture({{1, 1}, {1, 1}}), granny_other = typeOfSuture({{1, -1}, {1, -1}});
  EXPECT_EQ(granny.name, "granny");
  EXPECT_EQ(granny_other.name, "granny");
  EXPECT_EQ(granny_other.throws, std::vector<int>({-1, -1}));
  EXPECT_NE(granny.mirrored, granny_other.mirrored);
  // The surgeon's knot: a double throw, then a single one of the opposite sense; in the same
  // sense, the surgeon's granny. V is the product of the throws' (5₁ # 3₁*, 5₁ # 3₁).
  const KnotType surgeons = typeOfSuture({{2, 1}, {1, -1}});
  EXPECT_EQ(surgeons.name, "surgeon's") << toString(surgeons.jones);
  EXPECT_EQ(surgeons.throws, std::vector<int>({2, -1}));
  EXPECT_EQ(typeOfSuture({{2, -1}, {1, 1}}).name, "surgeon's");
  EXPECT_EQ(typeOfSuture({{2, 1}, {1, 1}}).name, "surgeon's granny");
  // The knot of the FLS suturing task: a surgeon's knot and one more single throw, reversed.
  const KnotType fls = typeOfSuture({{2, 1}, {1, -1}, {1, 1}});
  EXPECT_EQ(fls.name, "3 throws");
  EXPECT_EQ(fls.throws, std::vector<int>({2, 1, -1}));
  // Its mirror (every sense reversed) has other throws, and only one of the two is "mirrored".
  const KnotType fls_mirror = typeOfSuture({{2, -1}, {1, 1}, {1, -1}});
  EXPECT_EQ(fls_mirror.throws, std::vector<int>({-2, 1, -1}));
  EXPECT_NE(fls.mirrored, fls_mirror.mirrored);
}

TEST(KnotType, JonesPolynomialsAreWritten) {
  EXPECT_EQ(toString({{1, 1}, {3, 1}, {4, -1}}), "t + t^3 - t^4");
  EXPECT_EQ(toString({{-2, 1}, {-1, -1}, {0, 1}}), "t^-2 - t^-1 + 1");
  EXPECT_EQ(throwsString({2, -1}), "+2 -1");
  EXPECT_EQ(throwsString({}), "");
}

}  // namespace
}  // namespace filum::collision
