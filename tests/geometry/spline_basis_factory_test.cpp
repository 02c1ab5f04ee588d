// Building bases by name, as scene files will.
#include <gtest/gtest.h>

#include "filum/geometry/catmull_rom_spline.hpp"
#include "filum/geometry/knot_vector.hpp"
#include "filum/geometry/nonuniform_bspline.hpp"
#include "filum/geometry/spline_basis_factory.hpp"
#include "filum/geometry/uniform_cubic_bspline.hpp"

namespace filum::geometry {
namespace {

SplineBasisSpec spec(std::string name, int control_points, int degree = 3, std::vector<double> knots = {},
                     bool clamped = true) {
  SplineBasisSpec out;
  out.name = std::move(name);
  out.control_points = control_points;
  out.degree = degree;
  out.knots = std::move(knots);
  out.clamped = clamped;
  return out;
}

TEST(SplineBasisFactory, BuildsEveryKnownBasis) {
  EXPECT_EQ(makeSplineBasis(spec("uniform_cubic_bspline", 10))->name(), "uniform_cubic_bspline");
  EXPECT_EQ(makeSplineBasis(spec("catmull_rom", 10))->continuity(), 1);
  const auto clamped = makeSplineBasis(spec("nubs", 10, 4));
  EXPECT_EQ(clamped->degree(), 4);
  EXPECT_EQ(dynamic_cast<const NonUniformBSpline&>(*clamped).knots(), clampedUniformKnots(4, 10));
  const auto open = makeSplineBasis(spec("nubs", 10, 2, {}, false));
  EXPECT_EQ(dynamic_cast<const NonUniformBSpline&>(*open).knots(), uniformKnots(2, 10));
  const auto explicit_knots = makeSplineBasis(spec("nubs", 4, 2, {0, 0, 0, 0.3, 1, 1, 1}));
  EXPECT_EQ(explicit_knots->breakpoints(), (std::vector<double>{0.0, 0.3, 1.0}));
  EXPECT_EQ(splineBasisNames().size(), 3u);
}

TEST(SplineBasisFactory, ErrorsNameTheProblem) {
  auto message = [](const SplineBasisSpec& spec) {
    try {
      makeSplineBasis(spec);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message(spec("bezier", 4)).find("known: uniform_cubic_bspline, catmull_rom, nubs"), std::string::npos);
  EXPECT_NE(message(spec("catmull_rom", 3)).find("at least 4"), std::string::npos);
  EXPECT_NE(message(spec("nubs", 3, 3)).find("at least 4"), std::string::npos);
  EXPECT_NE(message(spec("nubs", 8, 7)).find("degree"), std::string::npos);
  EXPECT_NE(message(spec("nubs", 5, 2, {0, 0, 0, 0.3, 1, 1, 1})).find("4 control points"), std::string::npos);
  EXPECT_NE(message(spec("nubs", 4, 2, {0, 0, 0, 1, 0.3, 1, 1})).find("non-decreasing"), std::string::npos);
}

}  // namespace
}  // namespace filum::geometry
