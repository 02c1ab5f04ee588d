// The constant mass matrix of a dynamic spline (paper eq. 3):
//   M_ij = m ∫_0^1 b_i(s) b_j(s) ds,
// with m the mass per unit of parameter (constant along the curve, paper §3, so m equals the
// body's total mass since s ∈ [0, 1]). Computed exactly: on each polynomial piece b_i b_j has
// degree 2d, integrated exactly by d + 1 Gauss-Legendre nodes.
#pragma once

#include "filum/core/types.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::mechanics {

/// M (n × n, symmetric, banded with half-bandwidth = degree).
SparseMatrix massMatrix(const CurveBasis& basis, double mass);

/// w_i = ∫_0^1 b_i(s) ds, so the generalized gravity force is Q_i = m w_i g.
VecX basisIntegrals(const CurveBasis& basis);

}  // namespace filum::mechanics
