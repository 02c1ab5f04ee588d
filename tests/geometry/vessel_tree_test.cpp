// The lumen field of a vessel tree (geometry/vessel_tree.hpp) against the geometry it stands for:
// a cylinder's and a cone's distances in closed form, open and closed ends, the smooth maximum's
// bounds at a junction, the gradient against finite differences, the shipped data sets' anatomy,
// and bad input.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "filum/core/scene_error.hpp"
#include "filum/geometry/vessel_tree.hpp"

namespace filum::geometry {
namespace {

VesselTree::Branch straightBranch(const Vec3& a, const Vec3& b, double ra, double rb, bool open_start = false,
                                  bool open_end = false, const std::string& name = "tube") {
  VesselTree::Branch branch;
  branch.name = name;
  branch.points.resize(2, 3);
  branch.points.row(0) = a.transpose();
  branch.points.row(1) = b.transpose();
  branch.radii.resize(2);
  branch.radii << ra, rb;
  branch.open_start = open_start;
  branch.open_end = open_end;
  return branch;
}

// Round-off of a distance computed from coordinates of size L (a few operations): 1e-15 L.
constexpr double kRoundOff = 1e-14;

TEST(VesselTree, CylinderWallDistanceIsExact) {
  const double R = 5e-3, L = 0.1;
  const VesselTree tree({straightBranch(Vec3::Zero(), Vec3(0, 0, L), R, R)}, 0.0);
  for (double rho : {0.0, 1e-3, 4.5e-3, 5e-3, 6e-3})
    for (double z : {0.01, 0.05, 0.09}) {
      const Vec3 x(rho * std::cos(0.3), rho * std::sin(0.3), z);
      const VesselTree::Sample s = tree.sample(x, R);
      EXPECT_NEAR(s.value, R - rho, kRoundOff * L) << "rho " << rho << " z " << z;
      EXPECT_EQ(s.branch, 0);
      // The unit vector (x − c)/|x − c|: round-off of coordinates of size L over a length ρ.
      if (rho > 0.0) {
        EXPECT_NEAR((s.gradient + Vec3(std::cos(0.3), std::sin(0.3), 0)).norm(), 0.0, kRoundOff * L / rho);
      }
    }
}

TEST(VesselTree, TaperDistanceIsTheConesInItsMeridianPlane) {
  // A taper r(z) = r0 + k z: the distance of (z, ρ) to the line ρ = r0 + k z is
  // (r0 + k z − ρ) / √(1 + k²); φ / |∇φ| must be that, exactly, where the foot is on the segment.
  const double r0 = 6e-3, r1 = 3e-3, L = 0.05, k = (r1 - r0) / L;
  const VesselTree tree({straightBranch(Vec3::Zero(), Vec3(L, 0, 0), r0, r1)}, 0.0);
  for (double z : {0.01, 0.025, 0.04})
    for (double rho : {1e-3, 3e-3, 4.5e-3}) {
      const Vec3 x(z, 0, rho);
      const VesselTree::Sample s = tree.sample(x, r0);
      const double exact = (r0 + k * z - rho) / std::sqrt(1.0 + k * k);
      EXPECT_NEAR(s.value / s.gradient.norm(), exact, kRoundOff * L);
    }
}

TEST(VesselTree, OpenEndsGoOnStraightAndClosedEndsAreRound) {
  const double R = 4e-3, L = 0.02;
  const VesselTree open({straightBranch(Vec3::Zero(), Vec3(0, 0, L), R, R, true, true)}, 0.0);
  const VesselTree closed({straightBranch(Vec3::Zero(), Vec3(0, 0, L), R, R)}, 0.0);
  for (double beyond : {1e-3, 1e-2, 1.0}) {
    const Vec3 x(2e-3, 0, L + beyond);
    // Open: the tube goes on, the wall is R − ρ away whatever the distance beyond the end.
    EXPECT_NEAR(open.sample(x, 1.0).value, R - 2e-3, kRoundOff * (L + beyond));
    EXPECT_NEAR(open.sample(Vec3(2e-3, 0, -beyond), 1.0).value, R - 2e-3, kRoundOff * (L + beyond));
    // Closed: the end sphere, R − |x − p_end|.
    EXPECT_NEAR(closed.sample(x, 2.0).value, R - (x - Vec3(0, 0, L)).norm(), kRoundOff * (L + beyond));
  }
  // Capped (the picture): the flat end, φ = distance to the end plane inside the tube.
  EXPECT_NEAR(open.sample(Vec3(1e-3, 0, L - 5e-4), 1.0, true).value, 5e-4, kRoundOff * L);
  EXPECT_LT(open.sample(Vec3(1e-3, 0, L + 5e-4), 1.0, true).value, 0.0);
}

TEST(VesselTree, JunctionIsTheMaximumAwayFromItAndAFilletWithinTheBlend) {
  // A branch leaving a parent at right angles: the smooth maximum equals max(φ_parent, φ_branch)
  // where they differ by more than k, and lies in [max, max + k/4] everywhere (the polynomial
  // smooth maximum's bump h² k/4 is largest, k/4, where both are equal).
  const double k = 2e-3;
  const VesselTree tree({straightBranch(Vec3(-0.05, 0, 0), Vec3(0.05, 0, 0), 8e-3, 8e-3, true, true, "parent"),
                         straightBranch(Vec3::Zero(), Vec3(0, 0, 0.05), 3e-3, 3e-3, false, true, "branch")},
                        k);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  int blended = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 x(u(random), u(random), u(random) + 0.01);
    const double a = tree.branchValue(0, x), b = tree.branchValue(1, x), plain = std::max(a, b);
    if (plain < -0.01) continue;  // far outside: only a bound is computed there
    const double value = tree.sample(x, 0.02).value;
    EXPECT_GE(value, plain - kRoundOff);
    EXPECT_LE(value, plain + k / 4 + kRoundOff);
    if (std::abs(a - b) >= k) EXPECT_NEAR(value, plain, kRoundOff);
    else ++blended;
  }
  EXPECT_GT(blended, 10);  // the test did look at the fillet
  EXPECT_EQ(tree.branchAt(Vec3(0, 0, 0.03), 0.01), 1);
  EXPECT_EQ(tree.branchAt(Vec3(0.03, 0, 0), 0.01), 0);
}

TEST(VesselTree, GradientMatchesCentralDifferences) {
  // Central differences of step h err by O(h² φ''') plus round-off O(ε φ / h): with h = 1e-6 m on
  // fields of curvature ~1/r (r >= 3 mm) both are below 1e-6 of |∇φ| = O(1).
  const VesselTree tree = VesselTree::read(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/data/aortic_arch.json");
  std::mt19937 random(11);
  const Eigen::AlignedBox3d box = tree.bounds();
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double h = 1e-6;
  int checked = 0;
  for (int i = 0; i < 4000 && checked < 300; ++i) {
    Vec3 x;
    for (int c = 0; c < 3; ++c) x[c] = box.min()[c] + u(random) * (box.max()[c] - box.min()[c]);
    const VesselTree::Sample s = tree.sample(x, 0.02);
    if (s.branch < 0 || std::abs(s.value) > 4e-3) continue;  // near the wall, where contacts are
    Vec3 fd;
    for (int c = 0; c < 3; ++c) {
      Vec3 e = Vec3::Zero();
      e[c] = h;
      fd[c] = (tree.sample(x + e, 0.02).value - tree.sample(x - e, 0.02).value) / (2 * h);
    }
    // Creases (two segments of a bend equally near, a field's kink) are a set of measure zero;
    // a sample within h of one shows a jump, not an error of the formula: skip those.
    Vec3 fd_half;
    for (int c = 0; c < 3; ++c) {
      Vec3 e = Vec3::Zero();
      e[c] = h / 2;
      fd_half[c] = (tree.sample(x + e, 0.02).value - tree.sample(x - e, 0.02).value) / h;
    }
    if ((fd - fd_half).norm() > 1e-4) continue;
    EXPECT_NEAR((fd - s.gradient).norm(), 0.0, 1e-6) << x.transpose();
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST(VesselTree, ShippedTreesHaveTheirAnatomy) {
  const std::string data = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/data/";
  const VesselTree arch = VesselTree::read(data + "aortic_arch.json");
  ASSERT_EQ(arch.branchCount(), 4);
  for (const char* name : {"aorta", "brachiocephalic", "left_common_carotid", "left_subclavian"})
    EXPECT_GE(arch.branchIndex(name), 0) << name;
  // Radii of the adult anatomy, 4 to 15 mm.
  for (int b = 0; b < arch.branchCount(); ++b) {
    EXPECT_GE(arch.branch(b).radii.minCoeff(), 4e-3 - 1e-12);
    EXPECT_LE(arch.branch(b).radii.maxCoeff(), 15e-3 + 1e-12);
  }
  // The aneurysm: a dome 8 mm across, a neck 4 mm wide. Measured on the field: the zero crossings
  // along x through the dome's centre (0, 0, 15 mm) and through the neck just outside the parent's
  // wall (z = 10.5 mm), within the blend's bump k/4 = 0.25 mm (the smooth maximum of the largest
  // two fields) on each side and the bisection's 1 µm.
  const VesselTree sac = VesselTree::read(data + "cerebral_aneurysm.json");
  auto halfWidth = [&](double z) {
    double inside = 0.0, outside = 0.01;
    while (outside - inside > 1e-6) {
      const double mid = 0.5 * (inside + outside);
      (sac.sample(Vec3(mid, 0, z), 0.01).value > 0.0 ? inside : outside) = mid;
    }
    return inside;
  };
  EXPECT_NEAR(2 * halfWidth(15e-3), 8e-3, 2 * 0.25e-3 + 2e-6);
  EXPECT_NEAR(2 * halfWidth(10.5e-3), 4e-3, 2 * 0.25e-3 + 2e-6);
}

TEST(VesselTree, BadInputIsRefusedWithItsPlace) {
  auto refused = [](const std::string& text, const std::string& expected) {
    const nlohmann::json document = nlohmann::json::parse(text);
    const Params p(document, "tree.json", "");
    try {
      VesselTree::fromParams(p);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("tree.json"), std::string::npos) << e.what();
    }
  };
  refused(R"({"branches": []})", "/branches");
  refused(R"({"branches": [{"points": [[0, 0, 0, 1]]}]})", "/branches/0/points");
  refused(R"({"branches": [{"points": [[0, 0, 0, 1], [0, 0, 1]]}]})", "point 1");
  refused(R"({"branches": [{"points": [[0, 0, 0, 1], [0, 0, 1, -2]]}]})", "radius r > 0");
  refused(R"({"branches": [{"points": [[0, 0, 0, 1], [0, 0, 0, 1]]}]})", "distinct");
  refused(R"({"units": "inch", "branches": [{"points": [[0, 0, 0, 1], [0, 0, 1, 1]]}]})", "/units");
  refused(R"({"branches": [{"open": ["middle"], "points": [[0, 0, 0, 1], [0, 0, 1, 1]]}]})", "/open");
  refused(R"({"branches": [{"points": [[0, 0, 0, 1], [0, 0, 1, 1]], "radius": 3}]})", "radius");
  try {
    VesselTree::read("/nonexistent/tree.json");
    ADD_FAILURE() << "a missing file was read";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/tree.json"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace filum::geometry
