// CoilPacking (haptics/coil_packing.hpp): the aneurysm's volume against closed forms, the packing
// density's definition, and the refusals. The coil's length inside the aneurysm, on a rod, is
// checked in tests/apps/coil_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "filum/haptics/coil_packing.hpp"

namespace filum::haptics {
namespace {

using geometry::VesselTree;

VesselTree::Branch branch(const std::string& name, const std::vector<Vec3>& points, const std::vector<double>& radii) {
  VesselTree::Branch b;
  b.name = name;
  b.points.resize(static_cast<Eigen::Index>(points.size()), 3);
  b.radii.resize(static_cast<Eigen::Index>(radii.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    b.points.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
    b.radii[static_cast<Eigen::Index>(i)] = radii[i];
  }
  return b;
}

// A sac alone: a capsule of radius R = 4 mm and axis length a = 2 mm (a dome 8 mm across), and a
// parent artery far from it (the sac's cells are the sac's, none is the parent's).
VesselTree loneSac() {
  return VesselTree({branch("parent", {Vec3(0.03, 0, -0.01), Vec3(0.03, 0, 0.01)}, {2e-3, 2e-3}),
                     branch("sac", {Vec3(0, 0, 0.014), Vec3(0, 0, 0.016)}, {4e-3, 4e-3})},
                    0.0);
}

TEST(CoilPacking, SacVolumeIsTheCapsulesWithinTheLatticeDiscrepancy) {
  const VesselTree tree = loneSac();
  const double R = 4e-3, a = 2e-3;
  const double exact = M_PI * R * R * a + 4.0 / 3.0 * M_PI * R * R * R;  // cylinder + the two half balls
  for (const double h : {R / 25.0, R / 50.0}) {
    const CoilPacking packing(tree, {1}, h);
    // The midpoint count's error is the lattice-point discrepancy (coil_packing.hpp): for the
    // capsule, whose cylinder lies along a grid axis, relative O((h/R)^{4/3}); taken with
    // constant 1 (an order, not a proven bound): 1.4 % at h = R/25, 0.54 % at R/50.
    const double bound = std::pow(h / R, 4.0 / 3.0);
    const double error = std::abs(packing.volume() - exact) / exact;
    std::printf("  h = R/%.0f: V = %.2f mm³ against %.2f, error %.2e (bound %.1e)\n", R / h, 1e9 * packing.volume(),
                1e9 * exact, error, bound);
    EXPECT_LT(error, bound);
  }
}

TEST(CoilPacking, DefaultSpacingIsTheSmallestRadiusOverTwentyFive) {
  const CoilPacking packing(loneSac(), {1});
  EXPECT_DOUBLE_EQ(packing.spacing(), 4e-3 / 25.0);
}

TEST(CoilPacking, BranchesShareTheLumenWithoutCountingItTwice) {
  // Two sacs touching end to end along one axis: together they are one capsule of axis 2a + gap.
  // Counted as one aneurysm of both branches, the volume is the union's, not the sum.
  const double R = 3e-3;
  const VesselTree tree({branch("lower", {Vec3(0, 0, 0), Vec3(0, 0, 0.002)}, {R, R}),
                         branch("upper", {Vec3(0, 0, 0.002), Vec3(0, 0, 0.004)}, {R, R})},
                        0.0);
  const double h = R / 40.0;
  const double both = CoilPacking(tree, {0, 1}, h).volume();
  const double lower = CoilPacking(tree, {0}, h).volume(), upper = CoilPacking(tree, {1}, h).volume();
  const double exact = M_PI * R * R * 0.004 + 4.0 / 3.0 * M_PI * R * R * R;
  EXPECT_LT(std::abs(both - exact) / exact, std::pow(h / R, 4.0 / 3.0));
  // Each point belongs to one branch (the largest field): no point is in both parts.
  const CoilPacking lower_part(tree, {0}, R / 4), upper_part(tree, {1}, R / 4);
  for (double z = -R; z <= 0.004 + R; z += 1e-4)
    EXPECT_FALSE(lower_part.contains(Vec3(0.001, 0, z)) && upper_part.contains(Vec3(0.001, 0, z))) << "z = " << z;
  // The parts add up to the whole, each counted on its own grid (its own box): within the two
  // parts' discrepancies and half a layer of cells on each side of the flat cut between them
  // (π R² h / 2 each).
  const double layer = M_PI * R * R * h / both;
  EXPECT_LT(std::abs(lower + upper - both) / both, 2.0 * std::pow(h / R, 4.0 / 3.0) + layer);
}

TEST(CoilPacking, DensityIsCoilVolumeOverSacVolume) {
  const CoilPacking packing(loneSac(), {1});
  const double r = 0.127e-3, L = 0.1;
  EXPECT_DOUBLE_EQ(packing.density(M_PI * r * r * L), M_PI * r * r * L / packing.volume());
}

TEST(CoilPacking, ContainsOnlyTheAneurysmsBranchesInsideTheLumen) {
  const CoilPacking packing(loneSac(), {1});
  EXPECT_TRUE(packing.contains(Vec3(0, 0, 0.015)));
  EXPECT_TRUE(packing.contains(Vec3(0.0039, 0, 0.015)));
  EXPECT_FALSE(packing.contains(Vec3(0.0041, 0, 0.015)));  // outside the wall
  EXPECT_FALSE(packing.contains(Vec3(0.03, 0, 0.0)));      // in the parent artery
}

TEST(CoilPacking, RefusesNoBranchesAnUnknownBranchAndAGridTooFine) {
  const VesselTree tree = loneSac();
  EXPECT_THROW(CoilPacking(tree, {}), std::invalid_argument);
  EXPECT_THROW(CoilPacking(tree, {2}), std::invalid_argument);
  try {
    CoilPacking(tree, {1}, 1e-7);  // (10 mm / 0.1 µm)³ = 1e15 cells
    FAIL() << "a grid of 1e15 cells was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cells"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace filum::haptics
