// W from the blocks of A⁻¹ between the points the contact rows touch (point_inverse_blocks.hpp)
// against W from one column A⁻¹ l_r per row: the same matrix up to the order of its sums, so the
// same run. The capstan cord (capstan_scene.hpp: a silicone cord over a steel peg, implicit Euler
// 1 ms, the step matrix reused across steps) is run both ways, its settling pin let go at 0.1 s.
//
// Both runs solve Newton's steps by the dense LU ("newton_linear_solve": "dense"), so that W's
// formation is the only difference. (With steps through the band — about 110 of the run's
// Newton steps here — runs whose W differ by round-off part by 0.5 µm over the 300 steps, as
// much as the same W with and without the band steps do, measured: the steps' round-off on this
// nearly singular system, cond(W) up to ~1e10, moves Newton's iterates within the solve's
// tolerance, and the cord's motion with them.)
//
// Tolerance. The two W differ by round-off, ε |W| per entry; the contact solve is asked for a
// residual of 1e-12 (contact_tolerance) so that the runs' multipliers differ by that round-off
// amplified by cond(W + R) ≤ 1/ε_c = 1e6 (the compliance R = 1e-6 W_rr bounds it, on rows of
// similar W_rr), 1e-16 × 1e6 = 1e-10 of a step's velocity change from the contacts (g h = 1e-2
// m/s): 1e-12 m/s per step, 300 steps of h = 1 ms: 3e-13 m. Asserted: 1e-11 m (measured 5e-15),
// and the multipliers to 1e-9 of the cord's weight (measured 1e-11).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "capstan_scene.hpp"
#include "collision_scenes.hpp"
#include "filum/constraints/lagrange_multiplier_solver.hpp"

namespace filum::collision {
namespace {

struct CapstanRun {
  VecX q;
  VecX lambda;
  int point_block_solves = 0;
  long steps = 0;
};

CapstanRun runCapstan(bool point_blocks) {
  test::CapstanCord cord;
  cord.bending_modulus = cord.youngs_modulus;  // the solid cord these figures were measured with
  cord.settle = 0.1;
  nlohmann::json document = test::capstanScene(cord);
  document["constraint_solver"] = {{"type", "LagrangeMultiplierSolver"},
                                   {"point_blocks", point_blocks},
                                   {"newton_linear_solve", "dense"},
                                   {"contact_tolerance", 1e-12}};
  auto scene = test::loadCollisionScene(document);
  scene->init();
  CapstanRun run;
  for (run.steps = 0; run.steps < 300; ++run.steps) {
    const StepReport report = scene->step();
    EXPECT_TRUE(report.ok) << report.message;
    if (!report.ok) break;
    const auto* solver = dynamic_cast<const constraints::LagrangeMultiplierSolver*>(scene->constraintSolver());
    if (solver && solver->statistics().point_blocks) ++run.point_block_solves;
  }
  run.q = scene->state().q;
  run.lambda = scene->constraintSolver()->multipliers();
  return run;
}

TEST(PointInverseBlocks, GiveTheRunThatPerRowColumnsGive) {
  const CapstanRun points = runCapstan(true), columns = runCapstan(false);
  ASSERT_EQ(points.steps, 300);
  ASSERT_EQ(columns.steps, 300);
  double gap = 0.0;
  for (Eigen::Index i = 0; i < points.q.size(); ++i) gap = std::max(gap, std::abs(points.q[i] - columns.q[i]));
  const test::CapstanCord cord;
  const double length = cord.light_arm + M_PI * cord.wrapRadius() + cord.heavy_arm;
  const double weight = cord.density * M_PI * cord.radius * cord.radius * length * 9.81;
  ASSERT_EQ(points.lambda.size(), columns.lambda.size());
  const double force_gap = (points.lambda - columns.lambda).lpNorm<Eigen::Infinity>();
  std::printf("  point blocks on %d of 300 steps' last solves; positions %.3g m apart; multipliers %.3g of the weight\n",
              points.point_block_solves, gap, force_gap / weight);
  // The step matrix is reused across steps, so the held points' blocks serve most solves.
  EXPECT_GT(points.point_block_solves, 150);
  EXPECT_EQ(columns.point_block_solves, 0);
  EXPECT_LT(gap, 1e-11);
  EXPECT_LT(force_gap, 1e-9 * weight);
}

}  // namespace
}  // namespace filum::collision
