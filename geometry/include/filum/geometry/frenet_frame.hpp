// Frenet–Serret frame of a curve (do Carmo, "Differential Geometry of Curves and Surfaces" §1-5),
// in any parameterisation:
//   T = P'/|P'|,  B = (P' × P'')/|P' × P''|,  N = B × T,   curvature κ = |P' × P''| / |P'|³.
// It is undefined where P' = 0 or P'' ∥ P' (straight parts, inflections), and it flips and
// twists there; prefer rotation-minimizing frames for skinning.
#pragma once

#include <optional>

#include "filum/core/types.hpp"
#include "filum/geometry/curve_frame.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::geometry {

/// The Frenet frame at s, or nothing where it is undefined: |P'| = 0, or
/// |P' × P''| <= relative_threshold · |P'| |P''| (the angle between P' and P'' below the threshold).
std::optional<CurveFrame> frenetFrame(const CurveBasis& basis, ConstPointsRef q, double s,
                                      double relative_threshold = 1e-10);

/// Curvature κ(s) = |P' × P''| / |P'|³ (1/units of q); 0 where P' = 0.
double curveCurvature(const CurveBasis& basis, ConstPointsRef q, double s);

}  // namespace filum::geometry
