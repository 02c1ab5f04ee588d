// The diagram of a closed polygon projected along a direction (knot_determinant.cpp,
// knot_type.cpp): its crossings, each with the positions along the curve (edge index + edge
// parameter) of its over and under strands and its sign.
#pragma once

#include <vector>

#include "filum/core/types.hpp"

namespace filum::collision {

struct DiagramCrossing {
  double over;   // position along the curve of the over strand (the higher along d)
  double under;  // of the under strand
  int sign;      // +1 when o × u > 0 seen from +d (o, u the strands' directions), else −1
};

/// The crossings of non-adjacent projected edges; false if the projection is not generic (a
/// crossing at a vertex, strands that meet, parallel overlapping edges).
bool projectDiagram(const Points& closed, const Vec3& direction, std::vector<DiagramCrossing>& crossings);

}  // namespace filum::collision
