// The knot determinant |Δ(−1)| tells knots apart: 1 for the unknot, 3 for the trefoil (a closed
// overhand knot), 5 for the figure-eight knot, in every generic projection; an open overhand
// knot closed far away is a trefoil, an open straight or coiled thread an unknot.
#include <cmath>

#include <gtest/gtest.h>

#include "filum/collision/knot_determinant.hpp"

namespace filum::collision {
namespace {

template <class F>
Points sampleClosed(F f, int n) {
  Points p(n, 3);
  for (int k = 0; k < n; ++k) p.row(k) = f(2.0 * M_PI * k / n).transpose();
  return p;
}

Vec3 trefoil(double t) { return Vec3(std::sin(t) + 2 * std::sin(2 * t), std::cos(t) - 2 * std::cos(2 * t), -std::sin(3 * t)); }
Vec3 figureEight(double t) {
  return Vec3((2 + std::cos(2 * t)) * std::cos(3 * t), (2 + std::cos(2 * t)) * std::sin(3 * t), std::sin(4 * t));
}
Vec3 circle(double t) { return Vec3(std::cos(t), std::sin(t), 0.1 * std::sin(5 * t)); }

TEST(KnotDeterminant, TellsUnknotTrefoilAndFigureEightApart) {
  const std::vector<Vec3> directions = {Vec3(0.3137, 0.7288, 0.6087), Vec3(0.01, 0.02, 1.0), Vec3(0.9, -0.3, 0.2),
                                        Vec3(-0.2, 0.95, 0.1)};
  for (const Vec3& d : directions) {
    EXPECT_EQ(knotDeterminant(sampleClosed(circle, 80), d), 1);
    EXPECT_EQ(knotDeterminant(sampleClosed(trefoil, 90), d), 3);
    EXPECT_EQ(knotDeterminant(sampleClosed(figureEight, 120), d), 5);
  }
}

TEST(KnotDeterminant, AnOpenOverhandKnotClosedFarAwayIsATrefoil) {
  // The trefoil opened at its outer lobe t = π, with straight arms carried out along ±x.
  const int n = 90;
  Points open(n + 2, 3);
  for (int k = 0; k < n; ++k) open.row(k + 1) = trefoil(M_PI + 0.05 + (2 * M_PI - 0.1) * k / (n - 1)).transpose();
  open.row(0) = (open.row(1) + Eigen::RowVector3d(-5.0, 0.0, -2.0));
  open.row(n + 1) = (open.row(n) + Eigen::RowVector3d(5.0, 0.0, -2.0));
  EXPECT_EQ(knotDeterminant(closeFarAway(open)), 3);

  // A straight thread and a helix (coiled but not knotted) close to unknots.
  Points helix(200, 3);
  for (int k = 0; k < 200; ++k) helix.row(k) << std::cos(0.3 * k), std::sin(0.3 * k), 0.02 * k;
  EXPECT_EQ(knotDeterminant(closeFarAway(helix)), 1);
  Points line(2, 3);
  line << 0, 0, 0, 1, 0, 0;
  EXPECT_EQ(knotDeterminant(closeFarAway(line)), 1);
}

}  // namespace
}  // namespace filum::collision
