// The multiply-adds of one solve with a body's band factor (BlockInverse::bandBlocks), for the
// constraint solver's choices between a band and a dense way of doing the same product: both
// sweeps and the pivot, 9 per 3 × 3 block, 9 g (2 r + 1) for g block rows of half bandwidth r.
#pragma once

#include "filum/core/block_inverse.hpp"

namespace filum::constraints {

inline double bandSolveMultiplyAdds(const BandBlocks& band) { return 9.0 * band.groups * (2 * band.range + 1); }

}  // namespace filum::constraints
