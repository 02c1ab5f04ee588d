// GraspCoverage (grasp_coverage.hpp): the spans between consecutive grasps count when they are
// short steps, merge when they overlap, and a long jump counts nothing; lengths from the table.
#include <gtest/gtest.h>

#include "filum/haptics/grasp_coverage.hpp"

namespace filum::haptics {
namespace {

// A 2 m body whose length grows linearly with the abscissa: length(s) = 2 s.
GraspCoverage twoMetres(double max_step) {
  std::vector<double> table(11);
  for (int k = 0; k <= 10; ++k) table[k] = 0.2 * k;
  return GraspCoverage(table, max_step);
}

TEST(GraspCoverage, ShortStepsCountAndMergeALongJumpDoesNot) {
  GraspCoverage c = twoMetres(0.15);
  c.grasp(0.30);                                // the first grasp covers nothing yet
  EXPECT_DOUBLE_EQ(c.coveredLength(), 0.0);
  c.grasp(0.35);                                // 0.1 m on: [0.30, 0.35] → 0.1 m
  EXPECT_NEAR(c.coveredLength(), 0.1, 1e-15);
  c.grasp(0.32);                                // back within the span: nothing new
  EXPECT_NEAR(c.coveredLength(), 0.1, 1e-15);
  c.grasp(0.39);                                // 0.14 m on: merged into [0.30, 0.39]
  EXPECT_NEAR(c.coveredLength(), 0.18, 1e-15);
  c.grasp(0.60);                                // a 0.42 m jump: skipped
  EXPECT_NEAR(c.coveredLength(), 0.18, 1e-15);
  c.grasp(0.65);                                // a new span [0.60, 0.65]
  EXPECT_NEAR(c.coveredLength(), 0.28, 1e-15);
  EXPECT_NEAR(c.fraction(), 0.14, 1e-15);
  EXPECT_EQ(c.grasps(), 6);
}

TEST(GraspCoverage, ReadsLengthsBetweenTheTablesAbscissasLinearly) {
  GraspCoverage c({0.0, 0.1, 0.4}, 1.0);        // length 0.1 over [0, 0.5], 0.3 over [0.5, 1]
  EXPECT_DOUBLE_EQ(c.lengthAt(0.25), 0.05);
  EXPECT_DOUBLE_EQ(c.lengthAt(0.75), 0.25);
  EXPECT_DOUBLE_EQ(c.lengthAt(2.0), 0.4);       // clamped to the body
  c.grasp(0.25);
  c.grasp(0.75);
  EXPECT_DOUBLE_EQ(c.coveredLength(), 0.2);
  EXPECT_THROW(GraspCoverage({0.0}, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace filum::haptics
