// Builds any CurveBasis from a small description, for scene loaders:
//   "uniform_cubic_bspline"  UniformCubicBSpline(n)                 (C2, paper §2)
//   "catmull_rom"            CatmullRomSpline(n)                    (C1, interpolating)
//   "nubs"                   NonUniformBSpline(degree, knots)       (C^{d−m}, any knots)
// For "nubs" without explicit knots: clamped uniform knots (the curve runs from q_0 to q_{n−1})
// or, with clamped = false, uniform knots t_i = i − d.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "filum/geometry/spline_basis.hpp"

namespace filum::geometry {

struct SplineBasisSpec {
  std::string name = "uniform_cubic_bspline";
  int control_points = 0;     // n
  int degree = 3;             // "nubs" only, 1..5
  std::vector<double> knots;  // "nubs" only: n + degree + 1 values; empty → uniform
  bool clamped = true;        // "nubs" only, when knots is empty
};

/// The basis described by spec; throws std::invalid_argument with a message naming the problem
/// (unknown name — listing the known ones —, too few control points, bad degree or knots).
std::unique_ptr<CurveBasis> makeSplineBasis(const SplineBasisSpec& spec);

/// The names makeSplineBasis accepts.
const std::vector<std::string>& splineBasisNames();

}  // namespace filum::geometry
