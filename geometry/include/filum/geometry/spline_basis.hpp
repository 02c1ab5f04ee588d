// The spline bases of the geometry library implement the kernel's CurveBasis (core/curve_basis.hpp):
// the basis functions b_i(s) of a spline curve P(s) = Σ_i b_i(s) q_i (paper eq. 1), s ∈ [0, 1]
// the parametric abscissa along the whole curve.
//
// One interface for every basis (UniformCubicBSpline, CatmullRomSpline, NonUniformBSpline of
// degree 1..5; makeSplineBasis in spline_basis_factory.hpp builds any of them by name), so that
// mechanics, mappings and collision work with any of them. Bases are local: at any s only
// degree + 1 consecutive functions may be non-zero, reported as a BasisRow. All bases sum to
// one (Σ_i b_i(s) = 1, so rigid translations are exact); the B-spline bases are also
// non-negative (convex-hull property), Catmull-Rom is not (its functions dip to −2/27).
#pragma once

#include "filum/core/curve_basis.hpp"

namespace filum::geometry {

/// The kernel's basis row; the interface is filum::CurveBasis, one name in every library.
using BasisRow = filum::BasisRow;

}  // namespace filum::geometry
